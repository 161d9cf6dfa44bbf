// files.h - the host's one way to move bytes and float32 arrays to and from files, for the table
// generators, the conformance dump, the fuzzer corpus and the CUDA bridge:
//  - a whole file read at once;
//  - a file written atomically: a temporary next to it ("<path>.tmp"), renamed over it, so a
//    reader never sees half a table and a failed write leaves the old file;
//  - float32 values little-endian (IEEE 754 binary32, the shipped tables' .bin format): on a
//    little-endian host exactly the bytes of the array in memory.
// Errors throw std::runtime_error naming the path (and the system's reason where it has one).
#pragma once

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace openpbr::host {

// The bytes of the file, e.g. a 4096-byte .bin as a 4096-character string.
std::string read_whole_file(const std::filesystem::path& path);

// Replaces (or creates) the file with `bytes`, atomically.
void write_file_atomically(const std::filesystem::path& path, const std::string& bytes);

// float32 values as little-endian bytes (4 per value), and back; the bytes' size must be a
// multiple of 4.
std::string float32_little_endian_bytes(const std::vector<float>& values);
std::vector<float> floats_from_float32_little_endian(const std::string& bytes, const std::filesystem::path& source);

// A raw float32 file (e.g. `openpbr conformance --dump-cpu cpu.f32`): written atomically, read
// whole; a file whose size is not a multiple of 4 bytes is an error.
void write_float32_file(const std::filesystem::path& path, const std::vector<float>& values);
std::vector<float> read_float32_file(const std::filesystem::path& path);

}  // namespace openpbr::host
