#include "output/markdown_html.h"

#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string_view>
#include <vector>

#include "output/xml_text.h"

namespace peensim {

namespace {

// **bold** and `code` inside a line of text (escaped); other characters as they are.
std::string inline_html(std::string_view text) {
    std::string out;
    for (std::size_t i = 0; i < text.size();) {
        if (text[i] == '`') {
            const std::size_t end = text.find('`', i + 1);
            if (end != std::string_view::npos) {
                out += "<code>" + xml_text(text.substr(i + 1, end - i - 1)) + "</code>";
                i = end + 1;
                continue;
            }
        }
        if (text.substr(i, 2) == "**") {
            const std::size_t end = text.find("**", i + 2);
            if (end != std::string_view::npos) {
                out += "<strong>" + inline_html(text.substr(i + 2, end - i - 2)) + "</strong>";
                i = end + 2;
                continue;
            }
        }
        out += xml_text(text.substr(i, 1));
        ++i;
    }
    return out;
}

std::vector<std::string> table_cells(std::string_view row) {
    std::vector<std::string> cells;
    if (!row.empty() && row.front() == '|') row.remove_prefix(1);
    if (!row.empty() && row.back() == '|') row.remove_suffix(1);
    for (std::size_t start = 0;;) {
        const std::size_t bar = row.find('|', start);
        std::string_view cell = row.substr(start, bar == std::string_view::npos ? std::string_view::npos : bar - start);
        while (!cell.empty() && cell.front() == ' ') cell.remove_prefix(1);
        while (!cell.empty() && cell.back() == ' ') cell.remove_suffix(1);
        cells.emplace_back(cell);
        if (bar == std::string_view::npos) return cells;
        start = bar + 1;
    }
}

bool starts_with(std::string_view s, std::string_view prefix) { return s.substr(0, prefix.size()) == prefix; }

// "![alt](src)" filling the whole line: alt and src.
bool image_line(std::string_view line, std::string& alt, std::string& src) {
    if (!starts_with(line, "![") || line.back() != ')') return false;
    const std::size_t mid = line.find("](");
    if (mid == std::string_view::npos) return false;
    alt = std::string(line.substr(2, mid - 2));
    src = std::string(line.substr(mid + 2, line.size() - mid - 3));
    return true;
}

constexpr std::string_view kStyle =
    "body{font-family:sans-serif;max-width:72em;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}"
    "table{border-collapse:collapse;margin:1em 0;font-size:90%}th,td{border:1px solid #bbb;padding:0.25em 0.6em;text-align:left}"
    "th{background:#eee}code,pre{background:#f4f4f4;font-family:monospace}pre{padding:0.6em;overflow-x:auto}"
    "figure{margin:1em 0}img{max-width:100%}figcaption{color:#555;font-size:90%}";

}  // namespace

std::string base64(const std::string& bytes) {
    static constexpr char kDigits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t n = std::min<std::size_t>(3, bytes.size() - i);
        unsigned v = 0;
        for (std::size_t k = 0; k < 3; ++k) v = (v << 8) | (k < n ? static_cast<unsigned char>(bytes[i + k]) : 0u);
        for (std::size_t k = 0; k < 4; ++k) out += k <= n ? kDigits[(v >> (18 - 6 * k)) & 63u] : '=';
    }
    return out;
}

std::function<std::optional<std::string>(const std::string& src)> image_files_in(const std::string& directory) {
    return [directory](const std::string& src) -> std::optional<std::string> {
        std::ifstream file(std::filesystem::path(directory) / src, std::ios::binary);
        if (!file) return std::nullopt;
        return std::string(std::istreambuf_iterator<char>(file), {});
    };
}

std::string markdown_to_html(const std::string& markdown, const std::string& title,
                             const std::function<std::optional<std::string>(const std::string& src)>& image_bytes,
                             const std::map<std::string, std::string>& raw_blocks) {
    std::vector<std::string> lines;
    std::istringstream in(markdown);
    for (std::string l; std::getline(in, l);) lines.push_back(l);
    std::ostringstream h;
    h << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" << xml_text(title) << "</title>\n<style>"
      << kStyle << "</style>\n</head>\n<body>\n";
    std::string paragraph;  // text lines of the paragraph being read
    const auto end_paragraph = [&] {
        if (!paragraph.empty()) h << "<p>" << inline_html(paragraph) << "</p>\n";
        paragraph.clear();
    };
    for (std::size_t i = 0; i < lines.size();) {
        const std::string& line = lines[i];
        std::string alt, src;
        if (const auto block = raw_blocks.find(line); block != raw_blocks.end()) {
            end_paragraph();
            h << block->second;
            ++i;
        } else if (line.empty()) {
            end_paragraph();
            ++i;
        } else if (starts_with(line, "#")) {
            end_paragraph();
            std::size_t level = line.find_first_not_of('#');
            const std::size_t text_start = line.find_first_not_of(' ', level);
            h << "<h" << level << ">" << inline_html(text_start == std::string::npos ? "" : std::string_view(line).substr(text_start))
              << "</h" << level << ">\n";
            ++i;
        } else if (starts_with(line, "    ")) {
            end_paragraph();
            h << "<pre>";
            for (; i < lines.size() && (starts_with(lines[i], "    ") || lines[i].empty()); ++i)
                if (!lines[i].empty()) h << xml_text(std::string_view(lines[i]).substr(4)) << "\n";
            h << "</pre>\n";
        } else if (starts_with(line, "- ")) {
            end_paragraph();
            h << "<ul>\n";
            for (; i < lines.size() && starts_with(lines[i], "- "); ++i)
                h << "<li>" << inline_html(std::string_view(lines[i]).substr(2)) << "</li>\n";
            h << "</ul>\n";
        } else if (starts_with(line, "|") && i + 1 < lines.size() && starts_with(lines[i + 1], "|---")) {
            end_paragraph();
            h << "<table>\n<tr>";
            for (const std::string& c : table_cells(line)) h << "<th>" << inline_html(c) << "</th>";
            h << "</tr>\n";
            for (i += 2; i < lines.size() && starts_with(lines[i], "|"); ++i) {
                h << "<tr>";
                for (const std::string& c : table_cells(lines[i])) h << "<td>" << inline_html(c) << "</td>";
                h << "</tr>\n";
            }
            h << "</table>\n";
        } else if (image_line(line, alt, src)) {
            end_paragraph();
            const std::optional<std::string> bytes = image_bytes(src);
            const std::string target = bytes ? "data:image/png;base64," + base64(*bytes) : xml_text(src);
            h << "<figure><img src=\"" << target << "\" alt=\"" << xml_text(alt) << "\"><figcaption>" << inline_html(alt)
              << "</figcaption></figure>\n";
            ++i;
        } else {
            paragraph += (paragraph.empty() ? "" : " ") + line;
            ++i;
        }
    }
    end_paragraph();
    h << "</body>\n</html>\n";
    return h.str();
}

}  // namespace peensim
