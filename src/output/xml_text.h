// Text inside XML or HTML, as element content or a quoted attribute's value: the five characters
// that would end or start markup written as entities. One escape for the report's HTML and the
// ParaView collections' XML.
#pragma once

#include <string>
#include <string_view>

namespace peensim {

inline std::string xml_text(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (char c : text) {
        switch (c) {
            case '&': out += "&amp;"; break;
            case '<': out += "&lt;"; break;
            case '>': out += "&gt;"; break;
            case '"': out += "&quot;"; break;
            case '\'': out += "&#39;"; break;  // HTML 4 has no &apos;
            default: out += c;
        }
    }
    return out;
}

}  // namespace peensim
