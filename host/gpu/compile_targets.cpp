// `openpbr compile`: see compile_targets.h.
#include "host/gpu/compile_targets.h"

#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iomanip>
#include <sstream>
#include <stdexcept>

#include "host/gpu/build_tools.h"
#include "host/scene/features.h"
#include "host/support/stopwatch.h"

extern char** environ;

namespace openpbr::host {

namespace {

namespace fs = std::filesystem;

struct TargetInfo
{
    const char* name;
    const char* extension;
};

constexpr TargetInfo target_infos[] = {
    {"spirv", "spv"}, {"hlsl", "hlsl"}, {"metal", "metal"}, {"cuda", "cu"}, {"glsl", "glsl"}, {"wgsl", "wgsl"},
};

const char* extension_of(const std::string& target)
{
    for (const TargetInfo& info : target_infos)
    {
        if (target == info.name)
        {
            return info.extension;
        }
    }
    throw std::invalid_argument("unknown target '" + target + "'; known: spirv, hlsl, metal, cuda, glsl, wgsl, all");
}

std::string quote_command(const std::vector<std::string>& arguments)
{
    std::string text;
    for (const std::string& argument : arguments)
    {
        text += text.empty() ? "" : " ";
        text += argument.find_first_of(" \t'\"") == std::string::npos ? argument : "'" + argument + "'";
    }
    return text;
}

// Runs a command (no shell) and waits for it; returns its wall time. Its output goes to ours.
double run_command(const std::vector<std::string>& arguments)
{
    std::vector<char*> argv;
    for (const std::string& argument : arguments)
    {
        argv.push_back(const_cast<char*>(argument.c_str()));
    }
    argv.push_back(nullptr);
    const Stopwatch stopwatch;
    pid_t pid = 0;
    const int spawn_error = posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ);
    if (spawn_error != 0)
    {
        throw std::runtime_error("cannot run " + quote_command(arguments) + ": " + std::strerror(spawn_error));
    }
    int status = 0;
    while (waitpid(pid, &status, 0) < 0)
    {
        if (errno != EINTR)
        {
            throw std::runtime_error("waitpid failed for " + quote_command(arguments));
        }
    }
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
    {
        throw std::runtime_error("command failed (status " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) +
                                 "): " + quote_command(arguments));
    }
    return stopwatch.seconds();
}

// "-D NAME=0" arguments (Slang and the library generators take the same form) folding the
// options' toggle set; none without one.
std::vector<std::string> toggle_defines(const CompileTargetsOptions& options)
{
    std::vector<std::string> arguments;
    if (options.feature_mask)
    {
        for (const std::string& define : specialization_defines(*options.feature_mask))
        {
            arguments.insert(arguments.end(), {"-D", define});
        }
    }
    return arguments;
}

// The "-D" arguments of one target's Slang compile.
std::vector<std::string> slang_defines(const CompileTargetsOptions& options, const std::string& target)
{
    if (options.feature_mask)
    {
        return toggle_defines(options);
    }
    // Feature toggles (slang/openpbr_features.h): Slang turns specialization constants into
    // uniforms for HLSL and CUDA, so those outputs take compile-time permutations (SPIR-V keeps
    // them, Metal gets function constants).
    if (target == "hlsl" || target == "cuda")
    {
        return {"-D", "OPENPBR_SPECIALIZATION_CONSTANTS=0"};
    }
    return {};
}

// TARGETS: one target, or several separated by commas (slangc.mjs only, with -o DIR).
std::vector<std::string> slang_command(const CompileTargetsOptions& options, const std::string& targets,
                                       const std::vector<std::string>& defines)
{
    std::vector<std::string> command =
        options.slangc.empty()
            ? std::vector<std::string>{options.node,
                                       (fs::path(options.source_directory) / "targets" / "slangc.mjs").string(), "-q"}
            : std::vector<std::string>{options.slangc};
    command.insert(command.end(), {"-target", targets});
    command.insert(command.end(), defines.begin(), defines.end());
    return command;
}

CompiledFile record(const std::string& target, const std::string& description, const fs::path& path, double seconds)
{
    CompiledFile file;
    file.target = target;
    file.description = description;
    file.path = path.string();
    file.bytes = fs::file_size(path);
    file.seconds = seconds;
    return file;
}

// The targets asked for (none: "all"), "all" expanded, each once, in the order first named; an
// unknown name throws std::invalid_argument naming the known ones.
std::vector<std::string> expand_targets(const std::vector<std::string>& requested)
{
    std::vector<std::string> targets;
    for (const std::string& target : requested.empty() ? std::vector<std::string>{"all"} : requested)
    {
        const std::vector<std::string> expanded =
            target == "all" ? compile_target_names() : std::vector<std::string>{target};
        for (const std::string& name : expanded)
        {
            extension_of(name);
            if (std::find(targets.begin(), targets.end(), name) == targets.end())
            {
                targets.push_back(name);
            }
        }
    }
    return targets;
}

// Slang's outputs, one entry point at a time for each group of targets that take the same
// defines (slang_command): with slangc.mjs one process writes the whole group (-target a,b
// -o DIR -name NAME writes DIR/NAME.<ext>, moved here into each target's folder), since the
// WebAssembly compiler is loaded and started once per process: the conformance kernel for
// spirv, metal, glsl and wgsl in one process took 6.8 s of CPU against 4.5 s for spirv alone
// (2026-11-27), and the files are byte for byte those of one process per target. A native
// slangc (options.slangc) runs once per target.
struct SlangEntry
{
    const char* description;
    const char* entry;
    fs::path source_file;
    const char* output_name;  // file name without the extension
    // The render kernel: WGSL only, with every toggle an `override`; a driver that compiles
    // overrides unfolded (SwiftShader) builds kernels faster specialized when generated
    // (slangc.mjs -D OPENPBR_FEATURE_<NAME>=0; docs/specialization.md "WGSL: overrides or folded when generated").
    bool wgsl_only;
};

std::vector<SlangEntry> slang_entries(const fs::path& source)
{
    const fs::path kernels = source / "targets" / "kernels";
    return {
        {"conformance kernel (Slang)", "conformance_main", kernels / "conformance.slang", "conformance.slang", false},
        {"example shade_batch (Slang)", "shade_batch", source / "examples" / "shade_batch.slang", "shade_batch", false},
        {"render kernel (Slang)", "render_main", kernels / "render.slang", "render.slang", true},
    };
}

// The targets in groups that one slangc.mjs process compiles together (same defines), in the
// order first met; with a native slangc every target is a group of its own.
std::vector<std::vector<std::string>> slang_groups(const CompileTargetsOptions& options,
                                                   const std::vector<std::string>& targets)
{
    std::vector<std::vector<std::string>> groups;
    for (const std::string& target : targets)
    {
        const auto same_defines = [&](const std::vector<std::string>& group) {
            return options.slangc.empty() && slang_defines(options, group.front()) == slang_defines(options, target);
        };
        const auto group = std::find_if(groups.begin(), groups.end(),
                                        [&](std::vector<std::string>& candidate) { return same_defines(candidate); });
        if (group == groups.end())
        {
            groups.push_back({target});
        }
        else
        {
            group->push_back(target);
        }
    }
    return groups;
}

// One entry point for the members of one group it applies to (the render kernel: wgsl only),
// in one Slang run; each output file is recorded in `files`.
void compile_slang_entry(const CompileTargetsOptions& options, const SlangEntry& entry,
                         const std::vector<std::string>& group, std::vector<CompiledFile>& files)
{
    std::vector<std::string> members;
    for (const std::string& target : group)
    {
        if (!entry.wgsl_only || target == "wgsl")
        {
            members.push_back(target);
        }
    }
    if (members.empty() || (options.conformance_kernels_only && std::string(entry.entry) != "conformance_main"))
    {
        return;
    }
    std::string target_list;
    for (const std::string& target : members)
    {
        target_list += (target_list.empty() ? "" : ",") + target;
    }
    std::vector<std::string> command = slang_command(options, target_list, slang_defines(options, members.front()));
    const fs::path shared_output =
        fs::path(options.output_directory) / (std::string(".slang-") + entry.output_name + "-" + members.front());
    const fs::path single_output = fs::path(options.output_directory) / members.front() /
                                   (std::string(entry.output_name) + "." + extension_of(members.front()));
    const fs::path slang_dir = fs::path(options.source_directory) / "slang";
    command.insert(command.end(), {"-entry", entry.entry, "-stage", "compute", "-I", slang_dir.string()});
    if (members.size() > 1)
    {
        command.insert(command.end(), {"-o", shared_output.string(), "-name", entry.output_name});
    }
    else
    {
        command.insert(command.end(), {"-o", single_output.string()});
    }
    command.push_back(entry.source_file.string());
    const double seconds = run_command(command);
    for (const std::string& target : members)
    {
        const std::string extension = extension_of(target);
        const fs::path output =
            fs::path(options.output_directory) / target / (std::string(entry.output_name) + "." + extension);
        if (members.size() > 1)
        {
            fs::rename(shared_output / output.filename(), output);
        }
        files.push_back(record(target, entry.description, output, seconds));
    }
    if (members.size() > 1)
    {
        fs::remove_all(shared_output);
    }
}

// The WGSL library (generate_wgsl.mjs; not with conformance_kernels_only) and the conformance
// kernel over it, as the build makes path wgsl-library's (materials at binding 3, where every
// conformance kernel has them).
void generate_wgsl_library(const CompileTargetsOptions& options, std::vector<CompiledFile>& files)
{
    const std::string target = "wgsl";
    const fs::path source(options.source_directory);
    const fs::path slang_dir = source / "slang";
    const fs::path directory = fs::path(options.output_directory) / target;
    const fs::path generator = source / "targets" / "wgsl" / "generate_wgsl.mjs";
    const std::vector<std::string> defines = toggle_defines(options);
    if (!options.conformance_kernels_only)
    {
        const fs::path library_out = directory / "openpbr.wgsl";
        std::vector<std::string> library = {options.node, generator.string(), "-I", slang_dir.string()};
        library.insert(library.end(), defines.begin(), defines.end());
        library.insert(library.end(), {"-o", library_out.string()});
        files.push_back(record(target, "WGSL library (Slang module, plain names)", library_out, run_command(library)));
    }
    const fs::path library_kernel_out = directory / "conformance.library.wgsl";
    std::vector<std::string> library_kernel = {
        options.node, generator.string(), "-I", slang_dir.string(), "-D", "OPENPBR_WGSL_MATERIAL_BINDING=3"};
    library_kernel.insert(library_kernel.end(), defines.begin(), defines.end());
    library_kernel.insert(library_kernel.end(), {"-append", (source / "targets" / "wgsl" / "conformance.wgsl").string(),
                                                 "-o", library_kernel_out.string()});
    files.push_back(
        record(target, "conformance kernel over the WGSL library", library_kernel_out, run_command(library_kernel)));
}

// The HLSL library (headers flattened by generate_hlsl.mjs), the conformance kernel body for it
// and the kernel over it.
void generate_hlsl_library(const CompileTargetsOptions& options, std::vector<CompiledFile>& files)
{
    const std::string target = "hlsl";
    const fs::path source(options.source_directory);
    const fs::path slang_dir = source / "slang";
    const fs::path directory = fs::path(options.output_directory) / target;
    const fs::path generator = source / "targets" / "hlsl" / "generate_hlsl.mjs";
    const fs::path library_in = source / "targets" / "hlsl" / "openpbr.hlsl.in";
    const fs::path library_out = directory / "openpbr.hlsl";
    const std::vector<std::string> defines = toggle_defines(options);
    std::vector<std::string> library = {options.node, generator.string(), "-preset", "hlsl", "-I", slang_dir.string()};
    library.insert(library.end(), defines.begin(), defines.end());
    library.insert(library.end(), {"-o", library_out.string(), library_in.string()});
    files.push_back(record(target, "HLSL library (headers, flattened)", library_out, run_command(library)));
    const fs::path body_out = directory / "openpbr_conformance_kernel.hlsl";
    std::vector<std::string> body = {options.node, generator.string(), "-preset", "hlsl", "-I", slang_dir.string()};
    body.insert(body.end(), defines.begin(), defines.end());
    body.insert(body.end(), {"-provided", library_in.string(), "-o", body_out.string(),
                             (source / "targets" / "kernels" / "openpbr_conformance_kernel.h").string()});
    files.push_back(record(target, "conformance kernel body for the HLSL library", body_out, run_command(body)));
    const fs::path kernel_copy = directory / "conformance.hlsl";
    fs::copy_file(source / "targets" / "hlsl" / "conformance.hlsl", kernel_copy, fs::copy_options::overwrite_existing);
    files.push_back(record(target, "conformance kernel over the HLSL library", kernel_copy, 0.0));
}

}  // namespace

const std::vector<std::string>& compile_target_names()
{
    static const std::vector<std::string> names = [] {
        std::vector<std::string> list;
        for (const TargetInfo& info : target_infos)
        {
            list.push_back(info.name);
        }
        return list;
    }();
    return names;
}

CompileTargetsOptions default_compile_targets_options()
{
    CompileTargetsOptions options;
    options.source_directory = OPENPBR_COMPILE_SOURCE_DIR;
    options.node = OPENPBR_COMPILE_NODE;
    options.slangc = OPENPBR_COMPILE_SLANGC;
    return options;
}

std::vector<CompiledFile> compile_targets(const CompileTargetsOptions& options)
{
    if (options.output_directory.empty())
    {
        throw std::invalid_argument("no output directory");
    }
    const std::vector<std::string> targets = expand_targets(options.targets);
    for (const std::string& target : targets)
    {
        fs::create_directories(fs::path(options.output_directory) / target);
    }
    std::vector<CompiledFile> files;
    const std::vector<std::vector<std::string>> groups = slang_groups(options, targets);
    for (const SlangEntry& entry : slang_entries(options.source_directory))
    {
        for (const std::vector<std::string>& group : groups)
        {
            compile_slang_entry(options, entry, group, files);
        }
    }
    for (const std::string& target : targets)
    {
        if (target == "wgsl")
        {
            generate_wgsl_library(options, files);
        }
        if (target == "hlsl" && !options.conformance_kernels_only)
        {
            generate_hlsl_library(options, files);
        }
    }
    return files;
}

std::string to_text(const std::vector<CompiledFile>& files)
{
    std::ostringstream text;
    for (const CompiledFile& file : files)
    {
        text << std::left << std::setw(6) << file.target << std::right << std::setw(9) << file.bytes << " bytes "
             << std::fixed << std::setprecision(2) << std::setw(6) << file.seconds << " s  " << file.path << "  ("
             << file.description << ")\n";
    }
    return text.str();
}

}  // namespace openpbr::host
