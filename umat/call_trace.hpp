// A record of every UMAT call, for checking a finite element code's use of the UMAT at full
// precision (its own printout has seven digits): with the environment variable ECM_UMAT_TRACE
// naming a file, each call appends one line (docs/fe-codes.md, "Tracing the calls").
#pragma once

namespace ecm::umat {

struct TracedCall {
  int kstep, kinc, noel, npt, ntens, nstatv;
  const double* stran;   // NTENS, at the start
  const double* dstran;  // NTENS
  const double* stress;  // NTENS, at the end
  const double* statev;  // NSTATV, at the end
  double sse, spd, pnewdt;
};

// Appends the call to the trace file if ECM_UMAT_TRACE is set (thread-safe; a no-op otherwise).
void traceCall(const TracedCall& call);

}  // namespace ecm::umat
