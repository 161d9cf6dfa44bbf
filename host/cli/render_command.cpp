// `openpbr render`: gallery, furnace and CPU-versus-Vulkan comparison renders of the preview path
// tracer (host/preview/render.h). Exit status 0, or 1 on errors, a failed furnace check or a
// failed comparison.
#include "host/cli/command.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "host/preview/render.h"
#include "host/cli/output_files.h"

namespace openpbr::host {

struct RenderCommandOptions
{
    std::string backend = "cpu";
    std::vector<std::string> material_files;
    bool gallery = false;
    bool furnace = false;
    bool nested = false;        // the nested-media scenes (glass of water, air bubble in water)
    int samples_per_pixel = 0;  // 0: 32 for the gallery, 64 for the furnace
    std::string size;           // "WxH"
    int cell_size = 0;          // 0: 128 (gallery) or 64 (furnace), or from --size
    int columns = 0;
    std::uint32_t seed = 1;
    float exposure = 1.0f;
    int max_depth = 0;  // 0: 8 (gallery) or 32 (furnace)
    bool compare = false;
    float difference_scale = 8.0f;
    bool no_labels = false;
    bool quiet = false;
    std::string json;
    std::string linear;  // the linear image as JSON (mean and variance of the mean per pixel)
    std::string output;
};

namespace {

std::string stem_of(const std::string& path)
{
    const std::size_t slash = path.find_last_of('/');
    const std::size_t dot = path.find_last_of('.');
    return (dot != std::string::npos && (slash == std::string::npos || dot > slash)) ? path.substr(0, dot) : path;
}

nlohmann::json describe_render(const RenderImage& image, RenderBackend backend)
{
    return {{"backend", to_string(backend)},
            {"device", image.device},
            {"width", image.width},
            {"height", image.height},
            {"cell_size", image.cell_size},
            {"spp", image.samples_per_pixel},
            {"seconds", image.seconds},
            {"first_pass_seconds", image.first_pass_seconds},
            {"ns_per_pixel_sample", image.ns_per_pixel_sample},
            {"nonfinite_samples", image.nonfinite_samples}};
}

void print_render(const RenderImage& image, RenderBackend backend)
{
    std::printf("%s (%s): %dx%d px, %d spp, %.2f s (first pass %.2f s), %.0f ns per pixel-sample, "
                "%llu non-finite samples\n",
                to_string(backend), image.device.c_str(), image.width, image.height, image.samples_per_pixel, image.seconds,
                image.first_pass_seconds, image.ns_per_pixel_sample,
                static_cast<unsigned long long>(image.nonfinite_samples));
}

// Cell size from --size WxH: the largest square cells of the layout that fit.
int cell_from_size(const std::string& size, std::size_t count, int columns)
{
    int width = 0;
    int height = 0;
    char separator = 0;
    std::istringstream stream(size);
    if (!(stream >> width >> separator >> height) || (separator != 'x' && separator != 'X') || width < 8 || height < 8)
    {
        throw std::invalid_argument("--size expects WxH, e.g. 1024x896, got '" + size + "'");
    }
    const int cols = columns > 0 ? columns : std::max(1, int(std::ceil(std::sqrt(double(count)) - 1e-9)));
    const int rows = int((count + std::size_t(cols) - 1) / std::size_t(cols));
    return std::max(8, std::min(width / cols, height / rows));
}

}  // namespace

// Runs a parsed render command; returns the exit status (0 on success; 1 on errors, a failed
// furnace check or a failed comparison). Prints the output file names.
int run_render_command(const RenderCommandOptions& options, const std::string& materials_directory,
                       const std::string& kernel_directory);

CLI::App* add_render_subcommand(CLI::App& parent, const CommandContext& context)
{
    auto settings = std::make_shared<RenderCommandOptions>();
    RenderCommandOptions& options = *settings;
    CLI::App* render = parent.add_subcommand(
        "render", "path-trace a labelled gallery of material spheres (default: every bundled material)");
    render->add_option("--backend", options.backend, "cpu or vulkan")
        ->capture_default_str()
        ->check(CLI::IsMember({"cpu", "vulkan"}));
    render->add_option("--materials", options.material_files, "material files (default: the materials directory)");
    render->add_flag("--gallery", options.gallery,
                     "every bundled material, then the nested-media scenes (the default without --materials)");
    render->add_flag("--furnace", options.furnace,
                     "white furnace: white materials under a uniform white environment; checks 1 %");
    render->add_flag("--nested", options.nested,
                     "only the nested-media scenes (glass of water, air bubble in water; the gallery ends with them); "
                     "with --furnace their white versions");
    render->add_option("--spp", options.samples_per_pixel, "samples per pixel (default 32; furnace 64)")
        ->check(CLI::Range(1, 1 << 20));
    render->add_option("--size", options.size, "image size WxH; cells are the largest squares that fit");
    render->add_option("--cell", options.cell_size, "cell size in pixels (default 128; furnace 64)")
        ->check(CLI::Range(8, 4096));
    render->add_option("--columns", options.columns, "cells per row (default: about square)")->check(CLI::Range(1, 1024));
    render->add_option("--seed", options.seed, "random seed")->capture_default_str();
    render->add_option("--exposure", options.exposure, "exposure before tone mapping")->capture_default_str();
    render->add_option("--max-depth", options.max_depth, "surface events per path (default 8; furnace 32)")
        ->check(CLI::Range(1, 1024));
    render->add_flag("--compare", options.compare,
                     "render on both backends with the same seeds, write the difference, check RMSE < noise");
    render->add_option("--diff-scale", options.difference_scale, "scale of |cpu - vulkan| in the difference image")
        ->capture_default_str();
    render->add_flag("--no-labels", options.no_labels, "no material names in the image");
    render->add_flag("--quiet", options.quiet, "no progress bar");
    render->add_option("--json", options.json, "write timings and checks as JSON");
    render->add_option("--linear", options.linear,
                       "write the linear image as JSON: width, height, spp and, per pixel and channel (rows from "
                       "the top), the mean radiance and the variance of the mean (e.g. for the browser viewer's test)");
    render->add_option("-o,--output", options.output, "output PNG (default openpbr_gallery.png or openpbr_furnace.png)");
    render->callback([settings, context]() {
        run_command([&]() { return run_render_command(*settings, context.materials_directory, context.kernel_directory); });
    });
    return render;
}

int run_render_command(const RenderCommandOptions& options, const std::string& materials_directory,
                       const std::string& kernel_directory)
{
    try
    {
        // One cell per material; the gallery ends with the nested-media scenes, made of the
        // bundled Glass and the built-in water and air (host/preview/render.h).
        std::vector<Material> materials;
        const bool whole_gallery =
            !options.furnace && !options.nested && (options.gallery || options.material_files.empty());
        if (options.furnace && !options.nested)
        {
            materials = furnace_materials();
        }
        else if (whole_gallery)
        {
            materials = load_material_directory(materials_directory);
        }
        for (const std::string& file : options.material_files)
        {
            const std::vector<Material> loaded = load_materialx_file(file);
            materials.insert(materials.end(), loaded.begin(), loaded.end());
        }
        std::vector<RenderCell> cells = material_cells(materials);
        if (options.nested || whole_gallery)
        {
            const std::vector<RenderCell> nested = nested_media_cells(
                load_materialx_file(materials_directory + "/open_pbr_glass.mtlx").front(), options.furnace);
            cells.insert(cells.end(), nested.begin(), nested.end());
        }

        RenderSettings settings;
        settings.furnace = options.furnace;
        settings.columns = options.columns;
        settings.samples_per_pixel = options.samples_per_pixel > 0 ? options.samples_per_pixel : (options.furnace ? 64 : 32);
        settings.cell_size = options.furnace ? 64 : 128;
        if (!options.size.empty()) settings.cell_size = cell_from_size(options.size, cells.size(), options.columns);
        if (options.cell_size > 0) settings.cell_size = options.cell_size;
        settings.seed = options.seed;
        settings.max_depth = options.max_depth > 0 ? options.max_depth : (options.furnace ? 32 : 8);
        settings.progress = !options.quiet;
        settings.kernel_directory = kernel_directory;
        const std::string output =
            !options.output.empty() ? options.output : (options.furnace ? "openpbr_furnace.png" : "openpbr_gallery.png");
        const bool labels = !options.no_labels;
        nlohmann::json report;
        report["materials"] = materials.size();
        report["cells"] = cells.size();
        int status = 0;

        auto furnace_check = [&](const RenderImage& image, const std::string& name) {
            const std::vector<SphereStatistics> statistics = sphere_statistics(image, settings.environment);
            nlohmann::json spheres = nlohmann::json::array();
            std::printf("furnace (%s): environment %.3f, mean over each sphere's fully covered pixels:\n", name.c_str(),
                        settings.environment);
            for (const SphereStatistics& entry : statistics)
            {
                const bool pass = entry.relative_error <= 0.01 && entry.pixels > 0;
                status = pass ? status : 1;
                std::printf("  %-18s %.4f %.4f %.4f  error %.2f %%  (%zu px)  %s\n", entry.label.c_str(), entry.mean[0],
                            entry.mean[1], entry.mean[2], 100.0 * entry.relative_error, entry.pixels,
                            pass ? "ok" : "FAIL (> 1 %)");
                spheres.push_back({{"label", entry.label},
                                   {"mean", {entry.mean[0], entry.mean[1], entry.mean[2]}},
                                   {"relative_error", entry.relative_error},
                                   {"pixels", entry.pixels}});
            }
            report["furnace"][name] = spheres;
        };

        if (options.compare)
        {
            RenderSettings cpu_settings = settings;
            cpu_settings.progress_label = "cpu   ";
            RenderSettings vulkan_settings = settings;
            vulkan_settings.progress_label = "vulkan";
            const RenderImage cpu = render_cells(cells, cpu_settings, RenderBackend::cpu);
            print_render(cpu, RenderBackend::cpu);
            const RenderImage vulkan = render_cells(cells, vulkan_settings, RenderBackend::vulkan);
            print_render(vulkan, RenderBackend::vulkan);
            const RenderComparison comparison = compare_renders(cpu, vulkan);
            const std::string stem = stem_of(output);
            const std::string vulkan_path = stem + "_vulkan.png";
            const std::string difference_path = stem + "_diff.png";
            const std::string json_path = options.json.empty() ? stem + "_compare.json" : options.json;
            write_render_png(output, cpu, options.exposure, labels);
            write_render_png(vulkan_path, vulkan, options.exposure, labels);
            write_difference_png(difference_path, cpu, vulkan, options.difference_scale);
            const bool pass =
                comparison.rmse < comparison.noise && comparison.nonfinite_a == 0 && comparison.nonfinite_b == 0;
            status = pass ? 0 : 1;
            std::printf("compare: RMSE(cpu - vulkan) %.6g, Monte Carlo noise (RMS standard error) %.6g, ratio %.3f, "
                        "max |diff| %.4g, identical pixels %.2f %%, non-finite cpu %llu vulkan %llu: %s\n",
                        comparison.rmse, comparison.noise, comparison.noise > 0 ? comparison.rmse / comparison.noise : 0.0,
                        comparison.max_abs_difference, 100.0 * comparison.identical_fraction,
                        static_cast<unsigned long long>(comparison.nonfinite_a),
                        static_cast<unsigned long long>(comparison.nonfinite_b), pass ? "ok" : "FAIL");
            report["cpu"] = describe_render(cpu, RenderBackend::cpu);
            report["vulkan"] = describe_render(vulkan, RenderBackend::vulkan);
            report["compare"] = {{"rmse", comparison.rmse},
                                 {"noise", comparison.noise},
                                 {"max_abs_difference", comparison.max_abs_difference},
                                 {"identical_fraction", comparison.identical_fraction},
                                 {"pass", pass}};
            if (options.furnace)
            {
                furnace_check(cpu, "cpu");
                furnace_check(vulkan, "vulkan");
            }
            write_json_file(json_path, report);
            std::printf("wrote %s (cpu), %s (vulkan), %s (|cpu - vulkan| x %g), %s\n", output.c_str(), vulkan_path.c_str(),
                        difference_path.c_str(), double(options.difference_scale), json_path.c_str());
            return status;
        }

        const RenderBackend backend = options.backend == "vulkan" ? RenderBackend::vulkan : RenderBackend::cpu;
        const RenderImage image = render_cells(cells, settings, backend);
        print_render(image, backend);
        report["render"] = describe_render(image, backend);
        if (image.nonfinite_samples != 0) status = 1;
        if (options.furnace) furnace_check(image, to_string(backend));
        write_render_png(output, image, options.exposure, labels);
        std::printf("wrote %s\n", output.c_str());
        if (!options.linear.empty())
        {
            write_json_file(options.linear, {{"width", image.width},
                                             {"height", image.height},
                                             {"spp", image.samples_per_pixel},
                                             {"mean", image.mean},
                                             {"variance_of_mean", image.variance_of_mean}});
            std::printf("wrote %s\n", options.linear.c_str());
        }
        if (!options.json.empty())
        {
            write_json_file(options.json, report);
            std::printf("wrote %s\n", options.json.c_str());
        }
        return status;
    }
    catch (const std::exception& error)
    {
        std::cerr << "openpbr render: error: " << error.what() << "\n";
        return 1;
    }
}

}  // namespace openpbr::host
