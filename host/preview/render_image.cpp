// Tone mapping, labels and PNG output of the preview renderer; see render.h.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/preview/render.h"
#include "host/preview/render_font.h"
#include "host/scene/colour_spaces.h"

#if defined(__GNUC__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-parameter"
#pragma GCC diagnostic ignored "-Wsign-compare"
#pragma GCC diagnostic ignored "-Wunused-function"
#endif
#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#if defined(__GNUC__)
#pragma GCC diagnostic pop
#endif

namespace openpbr::host {

namespace {

// sRGB transfer function (IEC 61966-2-1) of a linear value in [0, 1].
float srgb_encode(float linear)
{
    const float x = std::clamp(linear, 0.0f, 1.0f);
    return x <= 0.0031308f ? 12.92f * x : 1.055f * std::pow(x, 1.0f / 2.4f) - 0.055f;
}

// ACES filmic tone curve, the fit of K. Narkowicz (2015), "ACES Filmic Tone Mapping Curve".
float aces_fit(float x)
{
    const float v = std::max(x, 0.0f);
    return std::clamp((v * (2.51f * v + 0.03f)) / (v * (2.43f * v + 0.59f) + 0.14f), 0.0f, 1.0f);
}

std::uint8_t to_byte(float encoded) { return std::uint8_t(std::clamp(std::lround(encoded * 255.0f), 0L, 255L)); }

void write_png(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb)
{
    if (!stbi_write_png(path.c_str(), width, height, 3, rgb.data(), width * 3))
    {
        throw std::runtime_error("cannot write PNG '" + path + "'");
    }
}

void draw_labels(std::vector<std::uint8_t>& rgb, const RenderImage& image)
{
    const int scale = std::max(1, image.cell_size / 160);
    const int margin = 2 * scale;
    const int line_height = (font::kGlyphHeight + 3) * scale;
    const std::uint8_t white[3] = {240, 240, 240};
    for (std::size_t cell = 0; cell < image.labels.size(); ++cell)
    {
        const int x0 = int(cell % std::size_t(image.columns)) * image.cell_size;
        const int y0 = int(cell / std::size_t(image.columns)) * image.cell_size;
        const std::vector<std::string> lines = font::wrap_text(image.labels[cell], image.cell_size - 2 * margin, scale);
        const int block = int(lines.size()) * line_height + margin;
        const int top = y0 + image.cell_size - block;
        font::darken_rectangle(rgb.data(), image.width, image.height, x0, top, x0 + image.cell_size, y0 + image.cell_size,
                               0.45f);
        for (std::size_t line = 0; line < lines.size(); ++line)
        {
            const int text_x = x0 + (image.cell_size - font::text_width(lines[line], scale)) / 2;
            font::draw_text(rgb.data(), image.width, image.height, text_x, top + margin + int(line) * line_height,
                            lines[line], scale, white);
        }
    }
    // One-pixel separators between cells.
    for (int y = 0; y < image.height; ++y)
    {
        for (int x = 0; x < image.width; ++x)
        {
            if ((x % image.cell_size == 0 && x > 0) || (y % image.cell_size == 0 && y > 0))
            {
                std::uint8_t* pixel = rgb.data() + (std::size_t(y) * std::size_t(image.width) + std::size_t(x)) * 3;
                pixel[0] = pixel[1] = pixel[2] = 20;
            }
        }
    }
}

}  // namespace

// The view transform (docs/colour.md): working space x exposure -> linear Rec.709 (the
// display's primaries; a component outside Rec.709 comes out negative and the tone curve clips
// it to 0) -> the ACES fit per channel -> the sRGB transfer function.
void write_render_png(const std::string& path, const RenderImage& image, float exposure, bool labels)
{
    std::vector<std::uint8_t> rgb(std::size_t(image.width) * std::size_t(image.height) * 3);
    for (std::size_t pixel = 0; pixel < rgb.size(); pixel += 3)
    {
        const glm::vec3 working(image.mean[pixel], image.mean[pixel + 1], image.mean[pixel + 2]);
        const glm::vec3 display = working_space_to_display(working * exposure);
        for (int channel = 0; channel < 3; ++channel)
        {
            rgb[pixel + std::size_t(channel)] = to_byte(srgb_encode(aces_fit(display[channel])));
        }
    }
    if (labels) draw_labels(rgb, image);
    write_png(path, image.width, image.height, rgb);
}

void write_difference_png(const std::string& path, const RenderImage& a, const RenderImage& b, float scale)
{
    if (a.width != b.width || a.height != b.height) throw std::invalid_argument("write_difference_png: sizes differ");
    std::vector<std::uint8_t> rgb(std::size_t(a.width) * std::size_t(a.height) * 3);
    for (std::size_t index = 0; index < rgb.size(); ++index)
    {
        rgb[index] = to_byte(srgb_encode(std::fabs(a.mean[index] - b.mean[index]) * scale));
    }
    write_png(path, a.width, a.height, rgb);
}

}  // namespace openpbr::host
