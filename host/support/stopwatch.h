// stopwatch.h - the host's one timer: wall time since construction on the steady clock, for
// the seconds and milliseconds reports of checks, studies and table generators. Header-only.
#pragma once

#include <chrono>

namespace openpbr::host {

class Stopwatch
{
  public:
    // Seconds since construction, e.g. 0.25.
    double seconds() const { return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
    double milliseconds() const { return seconds() * 1000.0; }

  private:
    std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace openpbr::host
