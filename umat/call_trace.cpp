// The UMAT's call trace (umat/call_trace.hpp): one line per call, every number as %.17g.
#include "umat/call_trace.hpp"

#include <cstdio>
#include <cstdlib>
#include <mutex>

namespace ecm::umat {

namespace {

// The file is opened on the first call (append, so that restarts and several processes add up).
std::FILE* traceFile() {
  static std::FILE* file = [] {
    const char* path = std::getenv("ECM_UMAT_TRACE");
    if (!path || !*path) return static_cast<std::FILE*>(nullptr);
    std::FILE* f = std::fopen(path, "a");
    if (!f) std::fprintf(stderr, "*WARNING in ecm umat: cannot open ECM_UMAT_TRACE=%s; no trace\n", path);
    else std::fputs("# kstep kinc noel npt | stran+dstran (NTENS) | stress (NTENS) | statev (NSTATV) | sse spd pnewdt\n", f);
    return f;
  }();
  return file;
}

}  // namespace

void traceCall(const TracedCall& c) {
  std::FILE* f = traceFile();
  if (!f) return;
  static std::mutex mutex;
  const std::lock_guard<std::mutex> lock(mutex);
  std::fprintf(f, "%d %d %d %d |", c.kstep, c.kinc, c.noel, c.npt);
  for (int i = 0; i < c.ntens; ++i) std::fprintf(f, " %.17g", c.stran[i] + c.dstran[i]);
  std::fputs(" |", f);
  for (int i = 0; i < c.ntens; ++i) std::fprintf(f, " %.17g", c.stress[i]);
  std::fputs(" |", f);
  for (int i = 0; i < c.nstatv; ++i) std::fprintf(f, " %.17g", c.statev[i]);
  std::fprintf(f, " | %.17g %.17g %.17g\n", c.sse, c.spd, c.pnewdt);
  std::fflush(f);
}

}  // namespace ecm::umat
