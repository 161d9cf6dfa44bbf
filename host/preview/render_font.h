// render_font.h - a tiny 5x7 bitmap font (capitals, digits, a little punctuation) for labels
// drawn into 8-bit RGB images; glyphs drawn for this project. Characters without a glyph
// draw as '?', lower case as upper case, '_' as a space.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace openpbr::host::font {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphHeight = 7;
constexpr int kGlyphAdvance = 6;  // one blank column between glyphs

// Width in pixels of one line of text at an integer scale (1 = 5x7 glyphs).
int text_width(const std::string& text, int scale);

// Draws text with its top-left corner at (x, y), clipped to the image, with a dark shadow.
void draw_text(std::uint8_t* rgb, int width, int height, int x, int y, const std::string& text, int scale,
               const std::uint8_t color[3]);

// Blends black over a rectangle [x0, x1) x [y0, y1) with the given opacity.
void darken_rectangle(std::uint8_t* rgb, int width, int height, int x0, int y0, int x1, int y1, float alpha);

// Splits text at spaces and underscores into lines of at most max_width pixels.
std::vector<std::string> wrap_text(const std::string& text, int max_width, int scale);

}  // namespace openpbr::host::font
