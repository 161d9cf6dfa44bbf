// Conformance paths run by other programs (CUDA, WebGPU): see cuda_conformance.h.
#include "host/gpu/cuda_conformance.h"

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <regex>
#include <filesystem>
#include <iterator>
#include <random>
#include <sstream>
#include <stdexcept>

#include "host/gpu/shipped_tables.h"
#include "host/support/files.h"

// Set by targets/CMakeLists.txt to the program's path when nvcc was found.
#ifndef OPENPBR_CUDA_CONFORMANCE_PROGRAM
#define OPENPBR_CUDA_CONFORMANCE_PROGRAM ""
#endif

namespace openpbr::host {

namespace {

namespace fs = std::filesystem;

const char* const cuda_path_names[] = {"cuda", "slang-cuda"};

// The driver's result file, or false when it is missing or not whole float32 values.
bool read_floats(const fs::path& path, std::vector<float>& values)
{
    try
    {
        values = read_float32_file(path);
        return true;
    }
    catch (const std::runtime_error&)
    {
        return false;
    }
}

std::string shell_quote(const std::string& text)
{
    std::string quoted = "'";
    for (const char c : text)
    {
        quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    }
    return quoted + "'";
}

std::vector<ExternalPathResult> not_executed(const std::vector<std::string>& names, const std::string& note)
{
    std::vector<ExternalPathResult> results;
    for (const std::string& name : names)
    {
        ExternalPathResult result;
        result.name = name;
        result.note = note;
        results.push_back(result);
    }
    return results;
}

}  // namespace

void write_conformance_inputs(const std::string& directory, const std::vector<float>& queries,
                              const std::vector<float>& materials)
{
    fs::create_directories(directory);
    write_float32_file(fs::path(directory) / "queries.f32", queries);
    write_float32_file(fs::path(directory) / "materials.f32", materials);
    write_float32_file(fs::path(directory) / "lut.f32", shipped_lut());
    write_float32_file(fs::path(directory) / "fuzz_ltc.f32", shipped_fuzz_ltc());
}

std::string default_cuda_conformance_program()
{
    if (const char* program = std::getenv("OPENPBR_CUDA_CONFORMANCE_PROGRAM"))
    {
        return program;
    }
    return OPENPBR_CUDA_CONFORMANCE_PROGRAM;
}

std::vector<ExternalPathResult> run_cuda_conformance_program(const std::string& program, const std::vector<float>& queries,
                                                             const std::vector<float>& materials)
{
    const std::vector<std::string> names(std::begin(cuda_path_names), std::end(cuda_path_names));
    if (program.empty())
    {
        return not_executed(names, "not built: nvcc was not found when the build was configured");
    }
    if (!fs::exists(program))
    {
        return not_executed(names, "not built: " + program + " does not exist (build target openpbr_cuda_programs)");
    }
    return run_conformance_program({program}, names, queries, materials);
}

std::vector<ExternalPathResult> run_conformance_program(const std::vector<std::string>& command_line,
                                                        const std::vector<std::string>& path_names,
                                                        const std::vector<float>& queries,
                                                        const std::vector<float>& materials)
{
    std::random_device seed;
    const fs::path directory = fs::temp_directory_path() / ("openpbr-paths-" + std::to_string(seed()));
    write_conformance_inputs(directory.string(), queries, materials);

    // The program prints one line per path ("<name>: executed on ..." or "<name>: skipped: ...").
    std::string command;
    for (const std::string& argument : command_line)
    {
        command += shell_quote(argument) + " ";
    }
    command += shell_quote(directory.string()) + " 2>&1";
    std::string output;
    int status = -1;
    if (FILE* pipe = popen(command.c_str(), "r"))
    {
        char buffer[4096];
        while (const std::size_t n = std::fread(buffer, 1, sizeof(buffer), pipe))
        {
            output.append(buffer, n);
        }
        status = pclose(pipe);
    }
    const int exit_code = status >= 0 && WIFEXITED(status) ? WEXITSTATUS(status) : -1;

    std::vector<ExternalPathResult> results = not_executed(path_names, "");
    for (ExternalPathResult& result : results)
    {
        std::istringstream lines(output);
        std::string line;
        const std::string prefix = result.name + ": ";
        while (std::getline(lines, line))
        {
            if (line.rfind(prefix, 0) == 0)
            {
                result.note = line.substr(prefix.size());
            }
        }
        if (result.note.empty())
        {
            result.note = "no result (exit status " + std::to_string(exit_code) + "): " + output;
        }
        if (result.note.rfind("executed", 0) == 0)
        {
            // "... = <ns> ns/query (CUDA events ...); eval <ns> ns/query, sample ..., pdf ..."
            const std::regex all_time("= ([0-9.eE+-]+) ns/query");
            const std::regex operation_time("(eval|sample|pdf) ([0-9.eE+-]+) ns/query");
            std::smatch match;
            if (std::regex_search(result.note, match, all_time))
            {
                result.device_ns_per_query["all"] = std::stod(match[1].str());
            }
            for (auto it = std::sregex_iterator(result.note.begin(), result.note.end(), operation_time);
                 it != std::sregex_iterator(); ++it)
            {
                result.device_ns_per_query[(*it)[1].str()] = std::stod((*it)[2].str());
            }
            result.executed = read_floats(directory / (result.name + ".results.f32"), result.results);
            if (!result.executed)
            {
                result.note = "executed, but " + result.name + ".results.f32 could not be read";
            }
        }
    }
    std::error_code ignored;
    fs::remove_all(directory, ignored);
    return results;
}

}  // namespace openpbr::host
