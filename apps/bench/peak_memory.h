#pragma once
// The process's peak resident set, per measurement: Linux keeps a high-water mark (VmHWM in
// /proc/self/status) that writing "5" to /proc/self/clear_refs resets to the current resident
// set, so a bench row can report the peak of its own run. Elsewhere (or without /proc) the
// reset does nothing and the peak reads 0.
namespace irad::apps {

// Resets the high-water mark to the current resident set (best effort).
void reset_peak_memory();
// The high-water mark since the last reset, in MiB (0 when unknown).
double peak_memory_mib();

} // namespace irad::apps
