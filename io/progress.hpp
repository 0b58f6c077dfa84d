#pragma once
// Progress of a long run on stderr. On a terminal: a bar with percent and ETA, redrawn in place
// (at most every 0.1 s). Otherwise (logs, CI): one plain line every `interval` seconds.
// finish() (or the destructor) prints one final line with the total time.
#include <chrono>
#include <cstdio>
#include <optional>
#include <string>

namespace ecm::io {

class Progress {
 public:
  struct Options {
    std::string label = "progress";
    double interval = 5.0;             // s between plain lines (non-terminal output)
    std::FILE* stream = stderr;
    std::optional<bool> terminal;      // force the terminal / plain mode (default: isatty)
  };

  Progress(double total, Options options);
  explicit Progress(double total) : Progress(total, Options{}) {}
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  // Reports that `done` of `total` units are complete (cheap when nothing is printed).
  void update(double done);
  // The final line ("label: done in 12.3 s"); later calls do nothing.
  void finish();

  bool terminal() const { return terminal_; }

 private:
  using Clock = std::chrono::steady_clock;
  double total_;
  Options options_;
  bool terminal_;
  bool finished_ = false;
  double done_ = 0.0;
  Clock::time_point start_;
  Clock::time_point lastPrint_;
  double seconds(Clock::time_point t) const;
  void print(double elapsed);
};

// "1:02:03", "2:03" or "45 s"-style durations for progress lines.
std::string formatDuration(double seconds);

}  // namespace ecm::io
