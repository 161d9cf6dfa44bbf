// The host's one file helper (host/support/files.h): float32 files round-trip bit for bit
// (signed zero, subnormal, infinity and NaN included), are little-endian (1.0f is 00 00 80 3F),
// leave no temporary behind, and a file that is not whole float32 values or is missing is an
// error naming the path.
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "host/support/files.h"

namespace {

using namespace openpbr::host;

class Files : public ::testing::Test
{
  protected:
    void SetUp() override
    {
        directory_ = std::filesystem::temp_directory_path() /
                     ("openpbr_test_files_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
        std::filesystem::remove_all(directory_);
        std::filesystem::create_directories(directory_);
    }
    void TearDown() override { std::filesystem::remove_all(directory_); }
    std::filesystem::path directory_;
};

TEST_F(Files, Float32RoundTripIsBitExact)
{
    const std::vector<float> values = {1.0f,
                                       -0.0f,
                                       std::numeric_limits<float>::denorm_min(),
                                       std::numeric_limits<float>::infinity(),
                                       std::numeric_limits<float>::quiet_NaN(),
                                       0.1f};
    const std::filesystem::path path = directory_ / "values.f32";
    write_float32_file(path, values);
    EXPECT_FALSE(std::filesystem::exists(directory_ / "values.f32.tmp"));
    const std::string bytes = read_whole_file(path);
    ASSERT_EQ(bytes.size(), values.size() * 4);
    EXPECT_EQ(bytes.substr(0, 4), std::string("\x00\x00\x80\x3f", 4));  // 1.0f, little-endian
    const std::vector<float> read = read_float32_file(path);
    ASSERT_EQ(read.size(), values.size());
    for (std::size_t i = 0; i < values.size(); ++i)
    {
        std::uint32_t written_bits = 0;
        std::uint32_t read_bits = 0;
        std::memcpy(&written_bits, &values[i], 4);
        std::memcpy(&read_bits, &read[i], 4);
        EXPECT_EQ(read_bits, written_bits) << "value " << i;
    }
}

TEST_F(Files, AtomicWriteReplacesTheWholeFile)
{
    const std::filesystem::path path = directory_ / "text.txt";
    write_file_atomically(path, "a longer first version\n");
    write_file_atomically(path, "short\n");
    EXPECT_EQ(read_whole_file(path), "short\n");
    write_float32_file(directory_ / "empty.f32", {});
    EXPECT_TRUE(read_float32_file(directory_ / "empty.f32").empty());
}

TEST_F(Files, BadFilesAreErrorsNamingThePath)
{
    const std::filesystem::path odd = directory_ / "odd.f32";
    write_file_atomically(odd, "12345");
    const std::filesystem::path missing = directory_ / "missing.f32";
    for (const std::filesystem::path& path : {odd, missing})
    {
        try
        {
            read_float32_file(path);
            FAIL() << "no exception for " << path;
        }
        catch (const std::runtime_error& error)
        {
            EXPECT_NE(std::string(error.what()).find(path.string()), std::string::npos) << error.what();
        }
    }
    EXPECT_THROW(write_file_atomically(directory_ / "no_such_directory" / "x.f32", "x"), std::runtime_error);
}

}  // namespace
