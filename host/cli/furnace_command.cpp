// `openpbr furnace`: the white furnace of host/checks/furnace.h as a table and, with --json FILE,
// as {"configs": [{"name": s, "cos_theta": c, "albedo": [r, g, b], ...}]}. Exit status 0 when
// every configuration is within its tolerance, 2 when one is not, 1 on errors (e.g. an
// unwritable JSON path, a --filter that matches nothing, or an unknown path). --paths runs the
// rows on GPU paths too (a path without a device is reported as not executed).
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/checks/furnace.h"
#include "host/cli/command.h"
#include "host/cli/output_files.h"

namespace openpbr::host {

namespace {

struct FurnaceSettings
{
    FurnaceOptions furnace;
    std::string json_path;  // e.g. furnace.json; empty = table only
};

int run_furnace(const FurnaceSettings& settings)
{
    std::vector<std::string> skipped;
    const std::vector<FurnaceRow> rows = run_white_furnace(settings.furnace, &skipped);
    for (const std::string& path : skipped)
    {
        std::cout << path << "\n";
    }
    if (rows.empty())
    {
        throw std::runtime_error("no configuration matches --filter '" + settings.furnace.name_filter + "'");
    }
    std::cout << furnace_to_text(rows);
    if (!settings.json_path.empty())
    {
        write_json_file(settings.json_path, furnace_to_json(rows));
        std::cout << "wrote " << settings.json_path << "\n";
    }
    std::size_t failures = 0;
    for (const FurnaceRow& row : rows)
    {
        failures += row.within_tolerance ? 0 : 1;
    }
    std::cout << rows.size() - failures << " of " << rows.size() << " within tolerance (";
    if (settings.furnace.film_grid)
    {
        std::cout << "albedo in [" << furnace_min_albedo(FurnaceExpectation::thin_film_grid, 1.0f) << ", "
                  << furnace_max_albedo << "] for cos >= " << furnace_tolerance_min_cos;
    }
    else
    {
        std::cout << "|1 - albedo| <= " << furnace_tolerance << " for cos >= " << furnace_tolerance_min_cos;
    }
    std::cout << ", albedo <= " << furnace_max_albedo << " everywhere, 3 standard errors; known limits: their bands)\n";
    return failures == 0 ? 0 : 2;
}

}  // namespace

CLI::App* add_furnace_subcommand(CLI::App& parent, const CommandContext& context)
{
    auto settings = std::make_shared<FurnaceSettings>();
    CLI::App* command = parent.add_subcommand("furnace", "white furnace: directional albedo of white configurations");
    command->add_option("--json", settings->json_path, "write {\"configs\": [...]} to this file");
    command->add_option("--samples", settings->furnace.samples, "samples per configuration and view")
        ->capture_default_str()
        ->check(CLI::Range(std::uint64_t(1024), std::uint64_t(1) << 32));
    command->add_option("--filter", settings->furnace.name_filter,
                        "only configurations whose name contains this, e.g. glass");
    command->add_option("--paths", settings->furnace.paths,
                        "paths to run, e.g. cpu slang-spirv (default: cpu; GPU paths take the rows at the default "
                        "wavelengths)");
    command->add_flag("--film", settings->furnace.film_grid,
                      "the filmed grid (film_furnace_configs in host/checks/furnace.h: 6804 rows) instead of the "
                      "specification's list");
    command->callback([settings, context]() {
        run_command([&]() {
            settings->furnace.kernel_directory = context.kernel_directory;
            return run_furnace(*settings);
        });
    });
    return command;
}

}  // namespace openpbr::host
