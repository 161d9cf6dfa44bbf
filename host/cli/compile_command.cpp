// `openpbr compile`: emits the shaders of every target (host/gpu/compile_targets.h) and prints
// what it wrote and how long each took. `--specialize` folds a toggle set when the files are
// generated, given as toggle names (coat,metal; base; all) and/or MaterialX files, whose
// materials' needs it takes (the same analysis as `openpbr features`). Exit status 0, or 1 on
// errors (e.g. a failed compiler, an unknown toggle, an unreadable file).
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "host/cli/command.h"
#include "host/gpu/compile_targets.h"
#include "host/scene/features.h"
#include "host/scene/material_library.h"

namespace openpbr::host {

namespace {

// The toggle set of --specialize's values: the union of the named toggles and of what each
// MaterialX file's materials need.
std::uint32_t specialization_mask(const std::vector<std::string>& values)
{
    std::vector<std::string> toggle_names;
    std::vector<Material> materials;
    const std::string extension = ".mtlx";
    for (const std::string& value : values)
    {
        const bool is_file = value.size() > extension.size() &&
                             value.compare(value.size() - extension.size(), extension.size(), extension) == 0;
        if (is_file)
        {
            const std::vector<Material> loaded = load_materialx_file(value);
            materials.insert(materials.end(), loaded.begin(), loaded.end());
        }
        else
        {
            toggle_names.push_back(value);
        }
    }
    return parse_feature_names(toggle_names) | scene_feature_mask(materials);
}

}  // namespace

CLI::App* add_compile_subcommand(CLI::App& parent, const CommandContext&)
{
    auto options = std::make_shared<CompileTargetsOptions>(default_compile_targets_options());
    auto specialize = std::make_shared<std::vector<std::string>>();
    CLI::App* command =
        parent.add_subcommand("compile", "emit the shaders of every target (SPIR-V, HLSL, Metal, CUDA, GLSL, WGSL)");
    command->add_option("--target", options->targets, "spirv, hlsl, metal, cuda, glsl, wgsl or all")
        ->delimiter(',')
        ->check(CLI::IsMember({"spirv", "hlsl", "metal", "cuda", "glsl", "wgsl", "all"}));
    command->add_option("-o,--output-dir", options->output_directory, "output directory")->required();
    command
        ->add_option("--specialize", *specialize,
                     "fold the feature toggles when generating: toggle names (e.g. coat,metal; base; all) and/or "
                     ".mtlx files whose materials' needs are kept; the rest compiled out")
        ->delimiter(',');
    command->callback([options, specialize]() {
        run_command([&]() {
            if (!specialize->empty())
            {
                options->feature_mask = specialization_mask(*specialize);
                std::cout << "specialized to {" << feature_set_label(*options->feature_mask) << "}\n";
            }
            std::cout << to_text(compile_targets(*options));
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
