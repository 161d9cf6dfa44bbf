// `openpbr fit CASE.json ...`: recovers each case's material parameters from its measurements by
// gradient descent with the module's own gradients (host/gradients/material_fit.h; the cases are
// in examples/fit/). Prints each parameter's start, fitted value and truth; exit 2 when a fitted
// value misses its tolerance.
#include "host/cli/command.h"

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "host/gradients/material_fit.h"
#include "host/support/files.h"

namespace openpbr::host {

namespace {

struct FitSettings
{
    std::vector<std::string> cases;
    std::string history_directory;
    std::size_t iterations = 0;  // 0: the case's
    std::size_t views = 0;       // 0: the case's
    std::size_t lights_per_view = 0;
};

int run_fit(const FitSettings& settings)
{
    bool all_within = true;
    for (const std::string& path : settings.cases)
    {
        FitCase fit_case = load_fit_case(path);
        if (settings.iterations > 0)
        {
            fit_case.iterations = settings.iterations;
        }
        if (settings.views > 0)
        {
            fit_case.views = settings.views;
        }
        if (settings.lights_per_view > 0)
        {
            fit_case.lights_per_view = settings.lights_per_view;
        }
        const std::vector<Measurement> measurements = make_measurements(fit_case);
        const FitResult result = fit_material(fit_case, measurements);
        std::printf("%s: %zu measurements (%zu views), noise %.3g, %zu iterations, %.1f s, loss %.3g -> %.3g: %s\n",
                    fit_case.name.c_str(), measurements.size(), fit_case.views, double(fit_case.noise), fit_case.iterations,
                    result.seconds, result.history.front().loss, result.history.back().loss,
                    result.within_tolerance ? "within tolerance" : "OUT OF TOLERANCE");
        const std::vector<std::string> names = fit_component_names(fit_case);
        std::size_t index = 0;
        for (const FitParameter& parameter : fit_case.parameters)
        {
            for (std::size_t component = 0; component < parameter.count; ++component, ++index)
            {
                std::printf("  %-34s start %8.4f  fitted %8.4f  truth %8.4f  (tolerance %.3g)\n", names[index].c_str(),
                            double(parameter.start[component]), double(result.fitted[index]),
                            double(parameter.truth[component]), double(parameter.tolerance));
            }
        }
        if (!settings.history_directory.empty())
        {
            const std::string file = settings.history_directory + "/" + fit_case.name + ".csv";
            write_file_atomically(file, fit_history_csv(fit_case, result));
            std::printf("  wrote %s\n", file.c_str());
        }
        all_within = all_within && result.within_tolerance;
    }
    return all_within ? 0 : 2;
}

}  // namespace

CLI::App* add_fit_subcommand(CLI::App& parent, const CommandContext& context)
{
    (void)context;
    auto settings = std::make_shared<FitSettings>();
    CLI::App* command = parent.add_subcommand(
        "fit", "recover materials' parameters from BSDF measurements by gradient descent with the module's gradients");
    command->add_option("cases", settings->cases, "fit cases, e.g. examples/fit/coated_metal.json")
        ->required()
        ->check(CLI::ExistingFile);
    command->add_option("--history", settings->history_directory,
                        "write each case's loss and parameters per iteration to DIR/<case>.csv (tools/plot_fit.py)");
    command->add_option("--iterations", settings->iterations, "iterations instead of the case's, e.g. 150");
    command->add_option("--views", settings->views, "measurement views instead of the case's, e.g. 16");
    command->add_option("--lights-per-view", settings->lights_per_view, "lights per view instead of the case's");
    command->callback([settings]() { run_command([&]() { return run_fit(*settings); }); });
    return command;
}

}  // namespace openpbr::host
