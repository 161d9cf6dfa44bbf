// The host's one progress reporter (host/support/progress.h) with stderr redirected to a file
// (not a terminal): one line per 10 % of the work with the label, nothing when disabled, the
// named step's text on its line, and a last line at finish when the work ended short of 100 %.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "host/support/progress.h"

namespace {

using namespace openpbr::host;

// The lines `body` writes to stderr, captured through a temporary file.
template <class Body> std::vector<std::string> stderr_lines_of(Body&& body)
{
    std::fflush(stderr);
    std::FILE* capture = std::tmpfile();
    const int saved = dup(fileno(stderr));
    dup2(fileno(capture), fileno(stderr));
    body();
    std::fflush(stderr);
    dup2(saved, fileno(stderr));
    close(saved);
    std::rewind(capture);
    std::string text;
    char buffer[256];
    while (std::fgets(buffer, sizeof buffer, capture))
    {
        text += buffer;
    }
    std::fclose(capture);
    std::vector<std::string> lines;
    std::istringstream stream(text);
    for (std::string line; std::getline(stream, line);)
    {
        lines.push_back(line);
    }
    return lines;
}

TEST(ProgressReporter, OneLinePerTenthWhenNotATerminal)
{
    const std::vector<std::string> lines = stderr_lines_of([] {
        ProgressReporter progress(200, true, "cells");
        for (int i = 0; i < 200; ++i)
        {
            progress.advance();
        }
        progress.finish();
    });
    ASSERT_EQ(lines.size(), 10u);
    EXPECT_EQ(lines.front().rfind("cells [###...", 0), 0u) << lines.front();
    EXPECT_NE(lines.front().find(" 10.0 %"), std::string::npos) << lines.front();
    EXPECT_NE(lines.back().find("100.0 %"), std::string::npos) << lines.back();
}

TEST(ProgressReporter, DisabledPrintsNothing)
{
    const std::vector<std::string> lines = stderr_lines_of([] {
        ProgressReporter progress(10, false, "quiet");
        progress.set_done(5);
        progress.begin_step("a step");
        progress.finish();
    });
    EXPECT_TRUE(lines.empty());
}

TEST(ProgressReporter, StepTextAndAShortFinish)
{
    // Four steps begun of five announced: the steps print at 0, 20, 40 and 60 % done (lines at
    // the 20, 40 and 60 % marks with their text), finish prints the 100 % line once.
    const std::vector<std::string> lines = stderr_lines_of([] {
        ProgressReporter progress(5, true);
        for (const char* step : {"first", "second", "third", "fourth"})
        {
            progress.begin_step(step);
        }
        progress.finish();
        progress.finish();
    });
    ASSERT_EQ(lines.size(), 4u);
    EXPECT_NE(lines[0].find("second"), std::string::npos) << lines[0];
    EXPECT_NE(lines[2].find("fourth"), std::string::npos) << lines[2];
    EXPECT_NE(lines[3].find("100.0 %"), std::string::npos) << lines[3];
    EXPECT_EQ(lines[3].rfind("[", 0), 0u) << "no label, no leading space: " << lines[3];
}

}  // namespace
