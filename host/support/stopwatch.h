// stopwatch.h - the host's timers: wall time since construction on the steady clock, for
// the seconds and milliseconds reports of checks, studies and table generators; and the CPU time
// of the calling thread, for per-query costs measured while other work shares the cores (a
// preempted thread's wall time counts the other work, its CPU time does not). Header-only.
#pragma once

#include <chrono>
#include <ctime>

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

// CPU seconds the constructing thread has run since construction (POSIX
// CLOCK_THREAD_CPUTIME_ID); read it on the same thread.
class ThreadCpuStopwatch
{
  public:
    double seconds() const { return now() - start_; }

  private:
    static double now()
    {
        timespec time{};
        clock_gettime(CLOCK_THREAD_CPUTIME_ID, &time);
        return double(time.tv_sec) + 1e-9 * double(time.tv_nsec);
    }
    double start_ = now();
};

}  // namespace openpbr::host
