// The `openpbr` command line: conformance and the other jobs of the host library.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "host/cli/accuracy_command.h"
#include "host/gpu/compile_targets.h"
#include "host/checks/conformance.h"
#include "host/cli/features_command.h"
#include "host/cli/furnace_command.h"
#include "host/tables/fuzz_fit.h"
#include "host/tables/lut_generator.h"
#include "host/scene/material_library.h"
#include "host/cli/render_command.h"
#include "host/cli/stability_command.h"
#include "host/cli/output_files.h"

#ifndef OPENPBR_DEFAULT_MATERIALS_DIR
#define OPENPBR_DEFAULT_MATERIALS_DIR "materials"
#endif
#ifndef OPENPBR_DEFAULT_GENERATED_DIR
#define OPENPBR_DEFAULT_GENERATED_DIR "slang/generated"
#endif
#ifndef OPENPBR_DEFAULT_KERNEL_DIR
#define OPENPBR_DEFAULT_KERNEL_DIR "kernels"
#endif

namespace {

std::vector<openpbr::host::Material> load_materials(const std::vector<std::string>& files, const std::string& directory)
{
    if (files.empty())
    {
        return openpbr::host::load_material_directory(directory);
    }
    std::vector<openpbr::host::Material> materials;
    for (const std::string& file : files)
    {
        const std::vector<openpbr::host::Material> loaded = openpbr::host::load_materialx_file(file);
        materials.insert(materials.end(), loaded.begin(), loaded.end());
    }
    return materials;
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"openpbr: OpenPBR 1.1 BSDF tools (conformance, table generation, ...)"};
    app.require_subcommand(1);

    std::string materials_directory = OPENPBR_DEFAULT_MATERIALS_DIR;
    std::vector<std::string> material_files;
    std::string kernel_directory = OPENPBR_DEFAULT_KERNEL_DIR;
    app.add_option("--materials-dir", materials_directory, "directory of .mtlx materials")->capture_default_str();
    app.add_option("--kernel-dir", kernel_directory, "directory of compiled kernels")->capture_default_str();

    CLI::App* conformance = app.add_subcommand("conformance", "compare every GPU path with the CPU build");
    openpbr::host::ConformanceOptions conformance_options;
    std::string conformance_json;
    bool validation = false;
    conformance->add_option("--queries", conformance_options.query_count, "number of queries")->capture_default_str()
        ->check(CLI::Range(std::size_t(1), std::size_t(100000000)));
    conformance->add_option("--seed", conformance_options.seed, "random seed")->capture_default_str();
    conformance->add_option("--json", conformance_json, "write the report as JSON");
    conformance->add_option("--paths", conformance_options.paths, "GPU paths to run (default: all)");
    conformance->add_option("--materials", material_files, "material files (default: the materials directory)");
    conformance->add_option("--dump-cpu", conformance_options.cpu_dump_path,
                            "write the CPU results as raw float32, e.g. cpu.f32 (bit-for-bit comparisons)");
    conformance->add_flag("--validation", validation, "enable Vulkan validation layers");
    conformance->add_flag("--specialize", conformance_options.specialize,
                          "one pipeline per feature-toggle set the materials need (default: the full pipeline)");

    CLI::App* lutgen = app.add_subcommand("lutgen", "generate the energy-compensation tables (Monte Carlo)");
    openpbr::host::LutGeneratorOptions lut_options;
    std::string lut_output_directory = OPENPBR_DEFAULT_GENERATED_DIR;
    lutgen->add_option("--size-2d", lut_options.size_2d, "nodes per axis of the 2D table")->capture_default_str()
        ->check(CLI::Range(2, 256));
    lutgen->add_option("--size-3d", lut_options.size_3d, "nodes on the view and roughness axes of the 3D tables")
        ->capture_default_str()->check(CLI::Range(2, 128));
    lutgen->add_option("--size-3d-eta", lut_options.size_3d_eta, "nodes on the eta axis of the 3D tables (even)")
        ->capture_default_str()->check(CLI::Range(6, 128));
    lutgen->add_option("--samples", lut_options.samples, "Monte Carlo samples per table cell")->capture_default_str()
        ->check(CLI::Range(1u, 1u << 30));
    lutgen->add_option("--bits", lut_options.bits, "32 (float) or 16 (values rounded to half precision)")
        ->capture_default_str()->check(CLI::IsMember({16, 32}));
    lutgen->add_option("--seed", lut_options.seed, "0 = the shipped tables; others give independent replicas")
        ->capture_default_str();
    lutgen->add_option("-o,--output-dir", lut_output_directory,
                       "where openpbr_lut_values.inc (array mode) and openpbr_lut.bin (buffer mode) go")
        ->capture_default_str();
    lutgen->add_flag("--progress", lut_options.progress_always, "print progress even when stderr is not a terminal");

    CLI::App* fuzzgen = app.add_subcommand("fuzzgen", "simulate the fuzz layer and fit its LTC table");
    openpbr::host::FuzzFitOptions fuzz_options;
    std::string fuzz_output_directory = OPENPBR_DEFAULT_GENERATED_DIR;
    fuzzgen->add_option("--photons", fuzz_options.photons, "photons per table cell")->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1024), std::uint64_t(1) << 34));
    fuzzgen->add_option("--seed", fuzz_options.seed, "base seed of the per-cell streams")->capture_default_str();
    fuzzgen->add_option("-o,--output-dir", fuzz_output_directory,
                        "where openpbr_fuzz_ltc_values.inc and openpbr_fuzz_ltc.bin go")->capture_default_str();
    fuzzgen->add_flag("--progress", fuzz_options.progress, "print a progress line per 10 %");

    CLI::App* compile = app.add_subcommand("compile", "emit the shaders of every target (SPIR-V, HLSL, Metal, CUDA, GLSL)");
    openpbr::host::CompileTargetsOptions compile_options = openpbr::host::default_compile_targets_options();
    compile->add_option("--target", compile_options.targets, "spirv, hlsl, metal, cuda, glsl or all")
        ->delimiter(',')->check(CLI::IsMember({"spirv", "hlsl", "metal", "cuda", "glsl", "all"}));
    compile->add_option("-o,--output-dir", compile_options.output_directory, "output directory")->required();

    openpbr::host::RenderCommand render = openpbr::host::add_render_subcommand(app);
    openpbr::host::FurnaceCommand furnace = openpbr::host::add_furnace_subcommand(app);
    openpbr::host::add_features_subcommands(app, materials_directory, kernel_directory);
    // Exit status 0 clean, 2 when a path produced a non-finite or negative output, 1 on errors.
    openpbr::host::add_stability_subcommand(app, OPENPBR_DEFAULT_STABILITY_CORPUS, kernel_directory);
    openpbr::host::add_bench_accuracy_subcommand(app);  // after "bench" exists (features)

    CLI11_PARSE(app, argc, argv);

    if (render.subcommand->parsed())
    {
        return openpbr::host::run_render_command(render, materials_directory, kernel_directory);
    }
    if (furnace.subcommand->parsed())
    {
        return openpbr::host::run_furnace_command(furnace);
    }

    try
    {
        if (compile->parsed())
        {
            std::cout << openpbr::host::to_text(openpbr::host::compile_targets(compile_options));
        }
        if (lutgen->parsed())
        {
            const std::vector<float> table = openpbr::host::generate_lut(lut_options);
            const std::string values_path = lut_output_directory + "/openpbr_lut_values.inc";
            const std::string binary_path = lut_output_directory + "/openpbr_lut.bin";
            openpbr::host::write_lut_values_inc(values_path, table, openpbr::host::describe(lut_options));
            openpbr::host::write_lut_binary(binary_path, table);
            std::cout << "wrote " << values_path << " and " << binary_path << " (" << table.size() << " values, "
                      << openpbr::host::describe(lut_options) << ")\n";
        }
        if (fuzzgen->parsed())
        {
            const std::vector<float> table = openpbr::host::generate_fuzz_table(fuzz_options);
            const std::string values_path = fuzz_output_directory + "/openpbr_fuzz_ltc_values.inc";
            const std::string binary_path = fuzz_output_directory + "/openpbr_fuzz_ltc.bin";
            openpbr::host::write_fuzz_values_inc(values_path, table);
            openpbr::host::write_fuzz_binary(binary_path, table);
            std::cout << "wrote " << values_path << " and " << binary_path << " (" << table.size() << " values)\n";
        }
        if (conformance->parsed())
        {
            conformance_options.kernel_directory = kernel_directory;
            conformance_options.validation = validation;
            const auto materials =
                openpbr::host::conformance_materials(load_materials(material_files, materials_directory));
            const openpbr::host::ConformanceReport report = openpbr::host::run_conformance(materials, conformance_options);
            std::cout << openpbr::host::to_text(report);
            if (!conformance_json.empty())
            {
                openpbr::host::write_json_file(conformance_json, openpbr::host::to_json(report));
                std::cout << "wrote " << conformance_json << "\n";
            }
        }
    }
    catch (const std::exception& error)
    {
        std::cerr << "openpbr: error: " << error.what() << "\n";
        return 1;
    }
    return 0;
}
