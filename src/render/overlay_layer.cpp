#include "render/overlay_layer.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <utility>

#include "render/label_layout.h"

namespace peensim::render {

namespace {

constexpr const char* kOverlayVertexShader = R"GLSL(#version 330 core
layout(location = 0) in vec2 pixel;
layout(location = 1) in vec2 texel;
layout(location = 2) in vec4 vertex_colour;
uniform vec2 viewport;
out vec2 uv;
out vec4 colour;
void main() {
    uv = texel;
    colour = vertex_colour;
    gl_Position = vec4(2.0 * pixel.x / viewport.x - 1.0, 1.0 - 2.0 * pixel.y / viewport.y, 0.0, 1.0);
}
)GLSL";

constexpr const char* kOverlayFragmentShader = R"GLSL(#version 330 core
in vec2 uv;
in vec4 colour;
uniform sampler2D atlas;
out vec4 fragment;
void main() {
    fragment = vec4(colour.rgb, colour.a * texture(atlas, uv).r);
}
)GLSL";

constexpr Rgba8 kTextColour{255, 255, 255, 255};
constexpr Rgba8 kShadowColour{0, 0, 0, 220};  // 1 px down-right: text reads on light and dark
constexpr Rgba8 kFrameColour{0, 0, 0, 200};

}  // namespace

OverlayLayer::OverlayLayer(FontAtlas atlas)
    : atlas_(std::move(atlas)),
      program_(gl::make_program("overlay", kOverlayVertexShader, kOverlayFragmentShader)),
      texture_(gl::make_texture()),
      vao_(gl::make_vertex_array()),
      buffer_(gl::make_buffer()) {
    u_viewport_ = gl::uniform(program_, "viewport");
    u_atlas_ = gl::uniform(program_, "atlas");
    glBindTexture(GL_TEXTURE_2D, texture_.get());
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_R8, atlas_.width(), atlas_.height(), 0, GL_RED, GL_UNSIGNED_BYTE, atlas_.pixels().data());
    // Glyphs are placed on whole pixels, so texels map 1:1 and need no filtering.
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glBindTexture(GL_TEXTURE_2D, 0);

    glBindVertexArray(vao_.get());
    glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
    gl::vertex_attribute(0, 2, GL_FLOAT, sizeof(Vertex), offsetof(Vertex, x), gl::Step::vertex);
    gl::vertex_attribute(1, 2, GL_FLOAT, sizeof(Vertex), offsetof(Vertex, u), gl::Step::vertex);
    gl::vertex_attribute(2, 4, GL_UNSIGNED_BYTE, sizeof(Vertex), offsetof(Vertex, colour), gl::Step::vertex);
    glBindVertexArray(0);
    gl::check_errors("while setting up the overlay");
}

void OverlayLayer::add_quad(float x0, float y0, float x1, float y1, float u0, float v0, float u1, float v1, Rgba8 top, Rgba8 bottom) {
    const Vertex a{x0, y0, u0, v0, top}, b{x1, y0, u1, v0, top}, c{x0, y1, u0, v1, bottom}, d{x1, y1, u1, v1, bottom};
    vertices_.insert(vertices_.end(), {a, b, c, b, d, c});
}

void OverlayLayer::add_solid(float x0, float y0, float x1, float y1, Rgba8 top, Rgba8 bottom) {
    const float u = static_cast<float>(FontAtlas::kSolidBlock) * 0.5f / static_cast<float>(atlas_.width());
    const float v = static_cast<float>(FontAtlas::kSolidBlock) * 0.5f / static_cast<float>(atlas_.height());
    add_quad(x0, y0, x1, y1, u, v, u, v, top, bottom);
}

void OverlayLayer::add_text(float x, float baseline, std::string_view text, Rgba8 colour) {
    const float inv_w = 1.0f / static_cast<float>(atlas_.width());
    const float inv_h = 1.0f / static_cast<float>(atlas_.height());
    float pen = std::round(x);
    const float base = std::round(baseline);
    for (char ch : text) {
        const FontAtlas::Glyph& g = atlas_.glyph(ch);
        if (g.width > 0 && g.height > 0) {
            const float x0 = pen + static_cast<float>(g.left);
            const float y0 = base - static_cast<float>(g.top);
            add_quad(x0, y0, x0 + static_cast<float>(g.width), y0 + static_cast<float>(g.height), static_cast<float>(g.x) * inv_w,
                     static_cast<float>(g.y) * inv_h, static_cast<float>(g.x + g.width) * inv_w, static_cast<float>(g.y + g.height) * inv_h,
                     colour, colour);
        }
        pen += static_cast<float>(g.advance);
    }
}

void OverlayLayer::add_shadowed_text(float x, float baseline, std::string_view text) {
    add_text(x + 1.0f, baseline + 1.0f, text, kShadowColour);
    add_text(x, baseline, text, kTextColour);
}

void OverlayLayer::add_colour_bar(int width, int height, const ColourBar& bar) {
    const float s = static_cast<float>(atlas_.pixel_height());
    const float margin = std::round(0.6f * s);
    const float bar_width = std::round(s);
    const float top = margin + std::round(1.9f * s);  // below the title and clear of its descenders
    const float bottom = top + std::round(0.45f * static_cast<float>(height));

    std::snprintf(label_, sizeof label_, "%.3g%s", bar.max * bar.label_scale, bar.label_unit.c_str());
    const std::string_view max_label(label_);
    const int max_width = atlas_.text_width(max_label);
    char min_text[sizeof label_];
    std::snprintf(min_text, sizeof min_text, "%.3g%s", bar.min * bar.label_scale, bar.label_unit.c_str());
    const std::string_view min_label(min_text);
    const float label_width = static_cast<float>(std::max(max_width, atlas_.text_width(min_label)));

    const float x1 = static_cast<float>(width) - margin - label_width - std::round(0.4f * s);
    const float x0 = x1 - bar_width;
    add_solid(x0 - 1.0f, top - 1.0f, x1 + 1.0f, bottom + 1.0f, kFrameColour, kFrameColour);
    const std::span<const Rgba> stops = bar.map.stops();
    const float step = (bottom - top) / static_cast<float>(stops.size() - 1);
    for (std::size_t i = 0; i + 1 < stops.size(); ++i) {  // stop 0 (min) at the bottom
        const float y_low = bottom - step * static_cast<float>(i);
        add_solid(x0, y_low - step, x1, y_low, to_rgba8(stops[i + 1]), to_rgba8(stops[i]));
    }
    const float label_x = x1 + std::round(0.4f * s);
    const float half_cap = 0.35f * s;  // centres the digits on the bar's ends
    add_shadowed_text(label_x, top + half_cap, max_label);
    add_shadowed_text(label_x, bottom + half_cap, min_label);
    const float title_x = std::min(x0, static_cast<float>(width) - margin - static_cast<float>(atlas_.text_width(bar.title)));
    add_shadowed_text(std::max(title_x, margin), margin + static_cast<float>(atlas_.ascender()), bar.title);
    if (std::isfinite(bar.mark)) add_mark(width, bar, x0, x1, top, bottom);
}

// The marked value: a white line across the bar (outlined in black, so it reads on every colour)
// with its label at the left; above the scale, a note under the bar instead.
void OverlayLayer::add_mark(int width, const ColourBar& bar, float x0, float x1, float top, float bottom) {
    const float s = static_cast<float>(atlas_.pixel_height());
    const float margin = std::round(0.6f * s);
    const float reach = std::round(0.3f * s);  // the line sticks out of the bar by this much
    if (bar.max > bar.min && bar.mark <= bar.max && bar.mark >= bar.min) {
        const float y = std::round(bottom - static_cast<float>((bar.mark - bar.min) / (bar.max - bar.min)) * (bottom - top));
        add_solid(x0 - reach - 1.0f, y - 2.0f, x1 + reach + 1.0f, y + 2.0f, kFrameColour, kFrameColour);
        add_solid(x0 - reach, y - 1.0f, x1 + reach, y + 1.0f, kTextColour, kTextColour);
        const float text_x = x0 - reach - std::round(0.3f * s) - static_cast<float>(atlas_.text_width(bar.mark_label));
        add_shadowed_text(std::max(text_x, margin), y + 0.35f * s, bar.mark_label);
        return;
    }
    const std::string note = bar.mark > bar.max ? bar.mark_label + ": above the scale" : bar.mark_label + ": below the scale";
    const float text_x = static_cast<float>(width) - margin - static_cast<float>(atlas_.text_width(note));
    add_shadowed_text(std::max(text_x, margin), bottom + std::round(1.6f * s), note);
}

void OverlayLayer::draw(int width, int height, std::span<const std::string> lines, const ColourBar* bar, std::span<const Label> labels) {
    vertices_.clear();
    const float margin = std::round(0.6f * static_cast<float>(atlas_.pixel_height()));
    float baseline = margin + static_cast<float>(atlas_.ascender());
    float widest = 0.0f;
    for (const std::string& line : lines) {
        add_shadowed_text(margin, baseline, line);
        baseline += static_cast<float>(atlas_.line_height());
        widest = std::max(widest, static_cast<float>(atlas_.text_width(line)));
    }
    if (bar != nullptr) add_colour_bar(width, height, *bar);
    // The labels, none over another nor over the text block.
    const LabelMetrics metrics{[this](const std::string& t) { return static_cast<float>(atlas_.text_width(t)); },
                               static_cast<float>(atlas_.ascender()), static_cast<float>(atlas_.line_height())};
    std::vector<LabelBox> taken;
    if (!lines.empty()) taken.push_back({0.0f, 0.0f, margin + widest + 2.0f, baseline - static_cast<float>(atlas_.line_height()) + margin});
    for (const Label& label : lay_out_labels(labels, metrics, width, height, std::move(taken))) {
        const float x = std::round(label.x_px - 0.5f * static_cast<float>(atlas_.text_width(label.text)));
        add_text(x + 1.0f, std::round(label.y_px) + 1.0f, label.text, kShadowColour);
        add_text(x, std::round(label.y_px), label.text, label.colour);
    }
    if (vertices_.empty()) return;

    glBindBuffer(GL_ARRAY_BUFFER, buffer_.get());
    if (vertices_.size() > buffer_capacity_) {
        buffer_capacity_ = vertices_.capacity();
        glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(buffer_capacity_ * sizeof(Vertex)), nullptr, GL_STREAM_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, static_cast<GLsizeiptr>(vertices_.size() * sizeof(Vertex)), vertices_.data());
    glUseProgram(program_.get());
    glUniform2f(u_viewport_, static_cast<float>(width), static_cast<float>(height));
    glUniform1i(u_atlas_, 0);
    glActiveTexture(GL_TEXTURE0);
    glBindTexture(GL_TEXTURE_2D, texture_.get());
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBindVertexArray(vao_.get());
    glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(vertices_.size()));
    glBindVertexArray(0);
    glDisable(GL_BLEND);
    glEnable(GL_DEPTH_TEST);
    glBindTexture(GL_TEXTURE_2D, 0);
}

}  // namespace peensim::render
