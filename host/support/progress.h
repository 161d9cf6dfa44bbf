// progress.h - the host's one progress reporter, for table generators, studies and the preview
// renderer. On stderr only, so stdout and every JSON output stay the same with or without it:
//  - stderr a terminal: one bar redrawn in place (at most every 0.1 s), e.g.
//    "cpu [#########.....................]  30.0 %  1.2 s elapsed, 2.8 s left  step text";
//  - otherwise (a log): the same text as one line per 10 % of the work.
// Work is counted in units (table cells, samples per pixel, named steps); advance() may be called
// from any thread.
#pragma once

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <mutex>
#include <string>

#include "host/support/stopwatch.h"

namespace openpbr::host {

// Whether stderr is a terminal (isatty), e.g. false when it is redirected to a file: the
// reporter's choice between a bar and lines, and the default of `openpbr lutgen`'s progress.
bool stderr_is_terminal();

class ProgressReporter
{
  public:
    // total: units of work, e.g. 4096 table cells (0 prints only at finish); enabled: false
    // prints nothing (e.g. --quiet); label: printed first, e.g. "cpu" (empty: none).
    ProgressReporter(std::uint64_t total, bool enabled, std::string label = {});

    // `count` more units done, from any thread; an update that finds another thread printing is
    // skipped, not queued.
    void advance(std::uint64_t count = 1);

    // The units done so far, e.g. the samples per pixel rendered after a pass.
    void set_done(std::uint64_t done);

    // A named step begins (e.g. "ground truth (random walk)"): the steps before it are done and
    // its text follows the bar until the next step.
    void begin_step(const std::string& text);

    // The work is complete: the last state (100 %) and, on a terminal, the line ends.
    void finish();

  private:
    void report(std::uint64_t done, bool force);
    void print(std::uint64_t done, double elapsed);

    const std::uint64_t total_;
    const bool enabled_;
    const bool terminal_;
    const std::string label_;
    const Stopwatch stopwatch_;
    std::atomic<std::uint64_t> done_{0};
    std::uint64_t steps_begun_ = 0;
    std::mutex mutex_;  // guards everything below and the printing
    std::string step_text_;
    double last_print_seconds_ = -1.0;
    int last_decile_ = 0;
    std::size_t last_length_ = 0;
    bool finished_ = false;
};

}  // namespace openpbr::host
