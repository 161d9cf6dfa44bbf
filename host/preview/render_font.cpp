// A tiny 5x7 bitmap font for the gallery's labels; see render_font.h.
#include "host/preview/render_font.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstdint>

namespace openpbr::host::font {

namespace {

// Each glyph as seven rows of five pixels, top to bottom, '#' set and '.' clear (drawn for
// this project). Letters are capitals only: lower case is drawn as upper case.
struct GlyphSource
{
    char character;
    const char* rows;  // "rrrrr rrrrr ... " (7 groups of 5)
};

constexpr GlyphSource kGlyphSources[] = {
    {'A', ".###. #...# #...# ##### #...# #...# #...#"}, {'B', "####. #...# #...# ####. #...# #...# ####."},
    {'C', ".###. #...# #.... #.... #.... #...# .###."}, {'D', "####. #...# #...# #...# #...# #...# ####."},
    {'E', "##### #.... #.... ####. #.... #.... #####"}, {'F', "##### #.... #.... ####. #.... #.... #...."},
    {'G', ".###. #...# #.... #.### #...# #...# .####"}, {'H', "#...# #...# #...# ##### #...# #...# #...#"},
    {'I', ".###. ..#.. ..#.. ..#.. ..#.. ..#.. .###."}, {'J', "..### ...#. ...#. ...#. ...#. #..#. .##.."},
    {'K', "#...# #..#. #.#.. ##... #.#.. #..#. #...#"}, {'L', "#.... #.... #.... #.... #.... #.... #####"},
    {'M', "#...# ##.## #.#.# #.#.# #...# #...# #...#"}, {'N', "#...# #...# ##..# #.#.# #..## #...# #...#"},
    {'O', ".###. #...# #...# #...# #...# #...# .###."}, {'P', "####. #...# #...# ####. #.... #.... #...."},
    {'Q', ".###. #...# #...# #...# #.#.# #..#. .##.#"}, {'R', "####. #...# #...# ####. #.#.. #..#. #...#"},
    {'S', ".#### #.... #.... .###. ....# ....# ####."}, {'T', "##### ..#.. ..#.. ..#.. ..#.. ..#.. ..#.."},
    {'U', "#...# #...# #...# #...# #...# #...# .###."}, {'V', "#...# #...# #...# #...# #...# .#.#. ..#.."},
    {'W', "#...# #...# #...# #.#.# #.#.# #.#.# .#.#."}, {'X', "#...# #...# .#.#. ..#.. .#.#. #...# #...#"},
    {'Y', "#...# #...# .#.#. ..#.. ..#.. ..#.. ..#.."}, {'Z', "##### ....# ...#. ..#.. .#... #.... #####"},
    {'0', ".###. #...# #..## #.#.# ##..# #...# .###."}, {'1', "..#.. .##.. ..#.. ..#.. ..#.. ..#.. .###."},
    {'2', ".###. #...# ....# ...#. ..#.. .#... #####"}, {'3', "##### ...#. ..#.. ...#. ....# #...# .###."},
    {'4', "...#. ..##. .#.#. #..#. ##### ...#. ...#."}, {'5', "##### #.... ####. ....# ....# #...# .###."},
    {'6', "..##. .#... #.... ####. #...# #...# .###."}, {'7', "##### ....# ...#. ..#.. .#... .#... .#..."},
    {'8', ".###. #...# #...# .###. #...# #...# .###."}, {'9', ".###. #...# #...# .#### ....# ...#. .##.."},
    {'-', "..... ..... ..... ##### ..... ..... ....."}, {'.', "..... ..... ..... ..... ..... .##.. .##.."},
    {'(', "...#. ..#.. .#... .#... .#... ..#.. ...#."}, {')', ".#... ..#.. ...#. ...#. ...#. ..#.. .#..."},
    {'%', "##... ##..# ...#. ..#.. .#... #..## ...##"}, {'/', "....# ....# ...#. ..#.. .#... #.... #...."},
    {':', "..... .##.. .##.. ..... .##.. .##.. ....."}, {'+', "..... ..#.. ..#.. ##### ..#.. ..#.. ....."},
    {'=', "..... ..... ##### ..... ##### ..... ....."}, {',', "..... ..... ..... ..... .##.. ..#.. .#..."},
    {'?', ".###. #...# ....# ...#. ..#.. ..... ..#.."},
};

using Glyph = std::array<std::uint8_t, kGlyphHeight>;  // bit 4 = leftmost column

struct GlyphTable
{
    std::array<Glyph, 128> glyphs{};
    std::array<bool, 128> present{};

    GlyphTable()
    {
        for (const GlyphSource& source : kGlyphSources)
        {
            Glyph glyph{};
            const char* cursor = source.rows;
            for (int row = 0; row < kGlyphHeight; ++row)
            {
                std::uint8_t bits = 0;
                for (int column = 0; column < kGlyphWidth; ++column)
                {
                    bits = std::uint8_t((bits << 1) | (*cursor == '#' ? 1 : 0));
                    ++cursor;
                }
                glyph[std::size_t(row)] = bits;
                if (*cursor == ' ') ++cursor;
            }
            const auto index = std::size_t(static_cast<unsigned char>(source.character));
            glyphs[index] = glyph;
            present[index] = true;
        }
    }
};

const GlyphTable& table()
{
    static const GlyphTable instance;
    return instance;
}

const Glyph* glyph_of(char character)
{
    if (character == ' ' || character == '_') return nullptr;  // blank
    unsigned char code = static_cast<unsigned char>(std::toupper(static_cast<unsigned char>(character)));
    if (code >= 128 || !table().present[code]) code = '?';
    return &table().glyphs[code];
}

void blend_pixel(std::uint8_t* rgb, int width, int height, int x, int y, const std::uint8_t color[3], float alpha)
{
    if (x < 0 || y < 0 || x >= width || y >= height) return;
    std::uint8_t* pixel = rgb + (std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3;
    for (int channel = 0; channel < 3; ++channel)
    {
        const float mixed = float(pixel[channel]) * (1.0f - alpha) + float(color[channel]) * alpha;
        pixel[channel] = std::uint8_t(std::clamp(mixed + 0.5f, 0.0f, 255.0f));
    }
}

void draw_glyphs(std::uint8_t* rgb, int width, int height, int x, int y, const std::string& text, int scale,
                 const std::uint8_t color[3], int offset_x, int offset_y)
{
    int pen = x;
    for (const char character : text)
    {
        if (const Glyph* glyph = glyph_of(character))
        {
            for (int row = 0; row < kGlyphHeight; ++row)
            {
                for (int column = 0; column < kGlyphWidth; ++column)
                {
                    if (((*glyph)[std::size_t(row)] >> (kGlyphWidth - 1 - column)) & 1)
                    {
                        for (int sy = 0; sy < scale; ++sy)
                        {
                            for (int sx = 0; sx < scale; ++sx)
                            {
                                blend_pixel(rgb, width, height, pen + column * scale + sx + offset_x,
                                            y + row * scale + sy + offset_y, color, 1.0f);
                            }
                        }
                    }
                }
            }
        }
        pen += kGlyphAdvance * scale;
    }
}

}  // namespace

int text_width(const std::string& text, int scale)
{
    if (text.empty()) return 0;
    return (int(text.size()) * kGlyphAdvance - (kGlyphAdvance - kGlyphWidth)) * scale;
}

void draw_text(std::uint8_t* rgb, int width, int height, int x, int y, const std::string& text, int scale,
               const std::uint8_t color[3])
{
    // A dark one-pixel shadow below and to the right keeps the text readable on any background.
    const std::uint8_t shadow[3] = {0, 0, 0};
    draw_glyphs(rgb, width, height, x, y, text, scale, shadow, scale, scale);
    draw_glyphs(rgb, width, height, x, y, text, scale, color, 0, 0);
}

void darken_rectangle(std::uint8_t* rgb, int width, int height, int x0, int y0, int x1, int y1, float alpha)
{
    const std::uint8_t black[3] = {0, 0, 0};
    for (int y = std::max(y0, 0); y < std::min(y1, height); ++y)
    {
        for (int x = std::max(x0, 0); x < std::min(x1, width); ++x)
        {
            blend_pixel(rgb, width, height, x, y, black, alpha);
        }
    }
}

std::vector<std::string> wrap_text(const std::string& text, int max_width, int scale)
{
    // Words split at spaces and underscores; a word longer than a line is cut.
    std::vector<std::string> words;
    std::string word;
    for (const char character : text)
    {
        if (character == ' ' || character == '_')
        {
            if (!word.empty()) words.push_back(word);
            word.clear();
        }
        else
        {
            word.push_back(character);
        }
    }
    if (!word.empty()) words.push_back(word);
    const int max_characters = std::max(1, (max_width / scale + (kGlyphAdvance - kGlyphWidth)) / kGlyphAdvance);
    std::vector<std::string> lines;
    std::string line;
    for (std::string& next : words)
    {
        if (int(next.size()) > max_characters) next.resize(std::size_t(max_characters));
        if (line.empty())
        {
            line = next;
        }
        else if (int(line.size() + 1 + next.size()) <= max_characters)
        {
            line += " " + next;
        }
        else
        {
            lines.push_back(line);
            line = next;
        }
    }
    if (!line.empty()) lines.push_back(line);
    return lines;
}

}  // namespace openpbr::host::font
