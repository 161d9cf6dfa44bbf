// output_files.h - how every subcommand writes its report files: one path for text and one for
// JSON (through nlohmann_json, indented by 2, newline-terminated), each throwing
// std::runtime_error("cannot write 'PATH'") when the file cannot be opened or written, which
// the subcommands turn into exit status 1.
#pragma once

#include <fstream>
#include <stdexcept>
#include <string>

#include <nlohmann/json.hpp>

namespace openpbr::host {

inline void write_text_file(const std::string& path, const std::string& text)
{
    std::ofstream file(path);
    if (!file)
    {
        throw std::runtime_error("cannot write '" + path + "'");
    }
    file << text;
    if (!file)
    {
        throw std::runtime_error("cannot write '" + path + "'");
    }
}

inline void write_json_file(const std::string& path, const nlohmann::json& json)
{
    write_text_file(path, json.dump(2) + "\n");
}

}  // namespace openpbr::host
