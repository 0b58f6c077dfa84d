#include "io/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <utility>

namespace ecm::io {

std::string formatDuration(double s) {
  if (!std::isfinite(s) || s < 0.0) return "?";
  if (s < 60.0) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.1f s", s);
    return buf;
  }
  const long total = std::lround(s);
  const long h = total / 3600, m = (total / 60) % 60, sec = total % 60;
  char buf[48];
  if (h > 0) {
    std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", h, m, sec);
  } else {
    std::snprintf(buf, sizeof buf, "%ld:%02ld", m, sec);
  }
  return buf;
}

Progress::Progress(double total, Options options)
    : total_(total > 0.0 ? total : 1.0),
      options_(std::move(options)),
      terminal_(options_.terminal ? *options_.terminal : ::isatty(::fileno(options_.stream)) == 1),
      start_(Clock::now()),
      lastPrint_(start_) {}

Progress::~Progress() { finish(); }

double Progress::seconds(Clock::time_point t) const { return std::chrono::duration<double>(t - start_).count(); }

void Progress::update(double done) {
  if (finished_) return;
  done_ = done >= 0.0 ? std::min(done, total_) : 0.0;  // (NaN -> 0: the bar's width is cast to an int)
  const Clock::time_point now = Clock::now();
  const double sinceLast = std::chrono::duration<double>(now - lastPrint_).count();
  if (sinceLast < (terminal_ ? 0.1 : options_.interval)) return;
  lastPrint_ = now;
  print(seconds(now));
}

void Progress::print(double elapsed) {
  const double fraction = done_ / total_;
  const double eta = fraction > 0.0 ? elapsed * (1.0 - fraction) / fraction : NAN;
  if (terminal_) {
    constexpr int width = 30;
    const int filled = static_cast<int>(fraction * width);
    std::string bar(static_cast<std::size_t>(filled), '#');
    bar.resize(width, '.');
    std::fprintf(options_.stream, "\r%s [%s] %5.1f%%  elapsed %s  ETA %s\033[K", options_.label.c_str(), bar.c_str(),
                 100.0 * fraction, formatDuration(elapsed).c_str(), formatDuration(eta).c_str());
  } else {
    std::fprintf(options_.stream, "%s: %5.1f%%  elapsed %s  ETA %s\n", options_.label.c_str(), 100.0 * fraction,
                 formatDuration(elapsed).c_str(), formatDuration(eta).c_str());
  }
  std::fflush(options_.stream);
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  const double elapsed = seconds(Clock::now());
  std::fprintf(options_.stream, "%s%s: done (%.1f%%) in %s\n", terminal_ ? "\r\033[K" : "", options_.label.c_str(),
               100.0 * done_ / total_, formatDuration(elapsed).c_str());
  std::fflush(options_.stream);
}

}  // namespace ecm::io
