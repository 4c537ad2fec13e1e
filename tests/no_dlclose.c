/* Preloaded in the sanitizer run only (tests/run_sanitizers.sh): dlclose() does nothing, so the
   libraries Mesa opens and closes again (its drivers, LLVM) are still mapped when LeakSanitizer
   reports at exit, and their stack frames carry the module names tests/lsan.supp matches. */
int dlclose(void* handle) {
  (void)handle;
  return 0;
}
