// files.cpp - see files.h.
#include "host/support/files.h"

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <system_error>

namespace openpbr::host {

namespace {

bool host_is_little_endian()
{
    const std::uint32_t probe = 1;
    unsigned char first = 0;
    std::memcpy(&first, &probe, 1);
    return first == 1;
}

std::uint32_t byte_swap(const std::uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0x0000FF00u) | ((v << 8) & 0x00FF0000u) | (v << 24);
}

}  // namespace

std::string read_whole_file(const std::filesystem::path& path)
{
    std::ifstream file(path, std::ios::binary);
    if (!file)
    {
        throw std::runtime_error("cannot open " + path.string() + ": " + std::strerror(errno));
    }
    std::ostringstream contents;
    contents << file.rdbuf();
    if (file.bad())
    {
        throw std::runtime_error("cannot read " + path.string());
    }
    return contents.str();
}

void write_file_atomically(const std::filesystem::path& path, const std::string& bytes)
{
    std::filesystem::path temporary = path;
    temporary += ".tmp";
    {
        std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
        if (!file)
        {
            throw std::runtime_error("cannot open " + temporary.string() + " for writing: " + std::strerror(errno));
        }
        file.write(bytes.data(), std::streamsize(bytes.size()));
        file.close();
        if (!file)
        {
            std::error_code ignored;
            std::filesystem::remove(temporary, ignored);
            throw std::runtime_error("cannot write " + temporary.string());
        }
    }
    std::error_code error;
    std::filesystem::rename(temporary, path, error);
    if (error)
    {
        std::error_code ignored;
        std::filesystem::remove(temporary, ignored);
        throw std::runtime_error("cannot rename " + temporary.string() + " to " + path.string() + ": " + error.message());
    }
}

std::string float32_little_endian_bytes(const std::vector<float>& values)
{
    std::string bytes(values.size() * sizeof(float), '\0');
    const bool swap = !host_is_little_endian();
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &values[i], sizeof bits);
        bits = swap ? byte_swap(bits) : bits;
        std::memcpy(&bytes[i * sizeof bits], &bits, sizeof bits);
    }
    return bytes;
}

std::vector<float> floats_from_float32_little_endian(const std::string& bytes, const std::filesystem::path& source)
{
    if (bytes.size() % sizeof(float) != 0)
    {
        throw std::runtime_error(source.string() + " has " + std::to_string(bytes.size()) +
                                 " bytes, not a whole number of float32 values");
    }
    std::vector<float> values(bytes.size() / sizeof(float));
    const bool swap = !host_is_little_endian();
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        std::uint32_t bits = 0;
        std::memcpy(&bits, &bytes[i * sizeof bits], sizeof bits);
        bits = swap ? byte_swap(bits) : bits;
        std::memcpy(&values[i], &bits, sizeof bits);
    }
    return values;
}

void write_float32_file(const std::filesystem::path& path, const std::vector<float>& values)
{
    write_file_atomically(path, float32_little_endian_bytes(values));
}

std::vector<float> read_float32_file(const std::filesystem::path& path)
{
    return floats_from_float32_little_endian(read_whole_file(path), path);
}

}  // namespace openpbr::host
