// `openpbr stability`: the hard-case corpus on the CPU build and every GPU path
// (host/checks/stability.h). Prints the text report as the run goes (the header and the paths
// to run, each path's block as it finishes, the volume checks, the verdict line last) and writes
// --json. Exit status 2 when any path produced a non-finite or negative output or a volume check
// failed, 1 on errors (e.g. a bad corpus).
#include "host/cli/command.h"

#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/checks/stability.h"
#include "host/cli/output_files.h"

namespace openpbr::host {

#ifndef OPENPBR_DEFAULT_STABILITY_CORPUS
#define OPENPBR_DEFAULT_STABILITY_CORPUS "tests/data/stability_corpus.json"
#endif

CLI::App* add_stability_subcommand(CLI::App& parent, const CommandContext& context)
{
    struct Settings
    {
        StabilityOptions options;
        std::string corpus;
        std::string json;
        std::string fuzz_corpus;
    };
    auto settings = std::make_shared<Settings>();
    settings->corpus = OPENPBR_DEFAULT_STABILITY_CORPUS;
    // The reference measurement (docs/stability.md): 10^6 samples per case on the CPU (about 2
    // minutes for the corpus on 2 cores), 10^5 on each GPU path (lavapipe runs about 10^6
    // queries/s there).
    settings->options.samples_per_case = 1000000;
    settings->options.gpu_samples_per_case = 100000;
    CLI::App* command = parent.add_subcommand(
        "stability", "hard-case corpus on the CPU build and every GPU path: non-finite, negative, energy gain");
    command->add_option("--corpus", settings->corpus, "stability corpus (JSON)")->capture_default_str();
    command->add_option("--samples", settings->options.samples_per_case, "extra samples per case")
        ->capture_default_str()
        ->check(CLI::Range(std::size_t(0), std::size_t(100000000)));
    command
        ->add_option("--gpu-samples", settings->options.gpu_samples_per_case,
                     "samples per case on GPU paths (0 = --samples)")
        ->capture_default_str();
    command->add_option("--seed", settings->options.seed, "random seed")->capture_default_str();
    command->add_option("--paths", settings->options.paths, "paths to run: cpu and GPU paths (default: all)");
    command->add_option("--json", settings->json, "write the report as JSON");
    command->add_flag("--validation", settings->options.validation, "enable Vulkan validation layers");
    command->add_option("--write-fuzz-corpus", settings->fuzz_corpus,
                        "write the fuzzer seed inputs (first three lights of each case) to this directory and exit");
    command->callback([settings, context]() {
        run_command([&]() {
            const std::vector<StabilityCase> cases = load_stability_corpus(settings->corpus);
            if (!settings->fuzz_corpus.empty())
            {
                const std::size_t count = write_fuzz_seed_corpus(cases, settings->fuzz_corpus);
                std::cout << "wrote " << count << " seed inputs to " << settings->fuzz_corpus << "\n";
                return 0;
            }
            StabilityOptions options = settings->options;
            options.kernel_directory = context.kernel_directory;
            // What the run does, then each path's block as it finishes, flushed: to a terminal or
            // to a log file alike (a run at the defaults takes minutes per path).
            const std::vector<std::string> paths = stability_paths(options);
            std::cout << stability_header_text(run_stability_cpu(cases, options, false));
            std::cout << "  running " << paths.size() << (paths.size() == 1 ? " path" : " paths")
                      << ", each reported as it finishes:";
            for (std::size_t index = 0; index < paths.size(); ++index)
            {
                std::cout << (index == 0 ? " " : ", ") << paths[index];
            }
            std::cout << std::endl;
            options.on_path_finished = [](const StabilityPathResult& path) { std::cout << to_text(path) << std::flush; };
            const StabilityReport report = run_stability(cases, options);
            std::cout << stability_volume_text(report);
            if (!settings->json.empty())
            {
                write_json_file(settings->json, to_json(report));
                std::cout << "wrote " << settings->json << "\n";
            }
            std::cout << verdict_line(stability_verdict(report)) << std::endl;
            if (has_violations(report))
            {
                std::cerr << "openpbr stability: non-finite or negative outputs found\n";
                return 2;
            }
            return 0;
        });
    });
    return command;
}

}  // namespace openpbr::host
