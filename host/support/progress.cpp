// progress.cpp - see progress.h. The one compiled file of host/support/: isatty is the
// platform's (POSIX unistd.h, or io.h on Windows), kept out of the header.
#include "host/support/progress.h"

#include <algorithm>
#include <cstdio>

#if defined(_WIN32)
#include <io.h>
#define OPENPBR_PROGRESS_ISATTY(fd) _isatty(fd)
#define OPENPBR_PROGRESS_FILENO(f) _fileno(f)
#else
#include <unistd.h>
#define OPENPBR_PROGRESS_ISATTY(fd) isatty(fd)
#define OPENPBR_PROGRESS_FILENO(f) fileno(f)
#endif

namespace openpbr::host {

namespace {

// Seconds between two redraws of the terminal bar, e.g. 0.1: fast enough to look live, rare
// enough that printing costs nothing next to the work.
constexpr double terminal_redraw_seconds = 0.1;

// Characters of the bar, e.g. 30.
constexpr int bar_width = 30;

}  // namespace

bool stderr_is_terminal() { return OPENPBR_PROGRESS_ISATTY(OPENPBR_PROGRESS_FILENO(stderr)) != 0; }

ProgressReporter::ProgressReporter(const std::uint64_t total, const bool enabled, std::string label)
    : total_(total), enabled_(enabled), terminal_(enabled && stderr_is_terminal()), label_(std::move(label))
{
}

void ProgressReporter::advance(const std::uint64_t count)
{
    const std::uint64_t done = done_.fetch_add(count, std::memory_order_relaxed) + count;
    report(done, false);
}

void ProgressReporter::set_done(const std::uint64_t done)
{
    done_.store(done, std::memory_order_relaxed);
    report(done, false);
}

void ProgressReporter::begin_step(const std::string& text)
{
    {
        const std::lock_guard<std::mutex> lock(mutex_);
        step_text_ = text;
    }
    const std::uint64_t done = steps_begun_++;
    done_.store(done, std::memory_order_relaxed);
    report(done, true);
}

void ProgressReporter::finish()
{
    if (!enabled_)
    {
        return;
    }
    const std::lock_guard<std::mutex> lock(mutex_);
    if (finished_)
    {
        return;
    }
    finished_ = true;
    step_text_.clear();
    const std::uint64_t done = std::max(total_, done_.load(std::memory_order_relaxed));
    if (terminal_)
    {
        print(done, stopwatch_.seconds());
        std::fputc('\n', stderr);
        std::fflush(stderr);
    }
    else if (last_decile_ < 10)
    {
        print(done, stopwatch_.seconds());
    }
}

void ProgressReporter::report(const std::uint64_t done, const bool force)
{
    if (!enabled_)
    {
        return;
    }
    std::unique_lock<std::mutex> lock(mutex_, std::defer_lock);
    if (force)
    {
        lock.lock();
    }
    else if (!lock.try_lock())
    {
        return;  // another thread is printing
    }
    if (finished_)
    {
        return;
    }
    const double elapsed = stopwatch_.seconds();
    if (terminal_)
    {
        if (force || last_print_seconds_ < 0.0 || elapsed - last_print_seconds_ >= terminal_redraw_seconds || done >= total_)
        {
            last_print_seconds_ = elapsed;
            print(done, elapsed);
        }
        return;
    }
    const int decile = total_ > 0 ? int(std::min<std::uint64_t>(10, done * 10 / total_)) : 0;
    if (decile > last_decile_)
    {
        last_decile_ = decile;
        print(done, elapsed);
    }
}

void ProgressReporter::print(const std::uint64_t done, const double elapsed)
{
    const double fraction = total_ > 0 ? std::min(1.0, double(done) / double(total_)) : 1.0;
    const int filled = std::min(bar_width, int(fraction * bar_width));
    std::string text = label_.empty() ? std::string() : label_ + " ";
    text += "[" + std::string(std::size_t(filled), '#') + std::string(std::size_t(bar_width - filled), '.') + "]";
    char numbers[96];
    char left[32] = "?";
    if (fraction >= 1.0)
    {
        std::snprintf(left, sizeof left, "0.0 s");
    }
    else if (fraction > 0.0)
    {
        std::snprintf(left, sizeof left, "%.1f s", elapsed * (1.0 - fraction) / fraction);
    }
    std::snprintf(numbers, sizeof numbers, " %5.1f %%  %.1f s elapsed, %s left", 100.0 * fraction, elapsed, left);
    text += numbers;
    if (!step_text_.empty())
    {
        text += "  " + step_text_;
    }
    if (terminal_)
    {
        // Redrawn in place: spaces cover what a longer previous line left.
        const std::size_t length = text.size();
        text.append(last_length_ > length ? last_length_ - length : 0, ' ');
        last_length_ = length;
        std::fprintf(stderr, "\r%s", text.c_str());
    }
    else
    {
        std::fprintf(stderr, "%s\n", text.c_str());
    }
    std::fflush(stderr);
}

}  // namespace openpbr::host
