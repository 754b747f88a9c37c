// SPDX-License-Identifier: MIT
// Transparent huge pages for the tool's own memory: glibc's malloc advises the kernel to back large allocations
// with 2 MB pages when GLIBC_TUNABLES has glibc.malloc.hugetlb=1 (glibc 2.35 and later), which removes most of
// the page faults and TLB misses of the distance tables, bases and embeddings (measured in
// docs/blended_maps.md, "Transparent huge pages").
// glibc reads that variable only when a process starts, so the tool starts itself once more with it set.
#pragma once

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#if defined(__linux__)
#include <unistd.h>
#endif

namespace shapestruct::cli {

/// How this process's malloc was started, in words for `-v` output: set by restart_with_huge_pages.
inline std::string& huge_pages_status() {
  static std::string status = "ordinary pages (restart_with_huge_pages was not called)";
  return status;
}

/// Starts this program again (same process id, same arguments) with glibc.malloc.hugetlb=1 added to
/// GLIBC_TUNABLES, unless that tunable is already there (the user's value is kept, whatever it is),
/// SHAPESTRUCT_HUGE_PAGES=0 asks not to, the program runs under valgrind (whose tools would not follow the new
/// image), the kernel has transparent huge pages off, or this is already the second start. Returns only when it
/// does not restart or the restart fails; the tool then runs as it would have, with ordinary pages. Must be
/// called before any thread or MPI starts.
inline void restart_with_huge_pages(char** argv) {
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
  (void)argv;
  huge_pages_status() = "the sanitizer's allocator (glibc's tunables do not apply)";
#elif defined(__linux__) && defined(__GLIBC__) && (__GLIBC__ > 2 || __GLIBC_MINOR__ >= 35)
  // The marker carries the user's GLIBC_TUNABLES ("-" when unset) across the restart; its presence also stops a
  // second restart where the loader drops GLIBC_TUNABLES (secure-execution mode).
  constexpr const char* marker = "SHAPESTRUCT_HUGE_PAGES_RESTARTED";
  auto restore = [](const std::string& original) {
    if (original == "-")
      unsetenv("GLIBC_TUNABLES");
    else
      setenv("GLIBC_TUNABLES", original.c_str() + 1, 1);
  };
  if (const char* restarted = std::getenv(marker); restarted != nullptr) {
    // malloc has read the tunables by now; anything the tool starts gets the user's environment.
    restore(restarted);
    unsetenv(marker);
    huge_pages_status() = "transparent huge pages (glibc.malloc.hugetlb=1; SHAPESTRUCT_HUGE_PAGES=0 turns them off)";
    return;
  }
  if (const char* choice = std::getenv("SHAPESTRUCT_HUGE_PAGES"); choice != nullptr && std::strcmp(choice, "0") == 0) {
    huge_pages_status() = "ordinary pages (SHAPESTRUCT_HUGE_PAGES=0)";
    return;
  }
  const char* preload = std::getenv("LD_PRELOAD");
  if (preload != nullptr && std::strstr(preload, "vgpreload") != nullptr) {
    huge_pages_status() = "ordinary pages (running under valgrind)";
    return;
  }
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.hugetlb") != nullptr) {
    huge_pages_status() = std::string("as GLIBC_TUNABLES sets (") + tunables + ")";
    return;
  }
  std::ifstream kernel_setting("/sys/kernel/mm/transparent_hugepage/enabled");
  const std::string thp((std::istreambuf_iterator<char>(kernel_setting)), std::istreambuf_iterator<char>());
  if (thp.empty() || thp.find("[never]") != std::string::npos) {
    huge_pages_status() = "ordinary pages (the kernel's transparent huge pages are off or missing)";
    return;
  }
  const std::string original = tunables != nullptr ? "=" + std::string(tunables) : std::string("-");
  const std::string value = tunables != nullptr && *tunables != '\0' ? std::string(tunables) + ":glibc.malloc.hugetlb=1"
                                                                     : std::string("glibc.malloc.hugetlb=1");
  if (setenv(marker, original.c_str(), 1) == 0 && setenv("GLIBC_TUNABLES", value.c_str(), 1) == 0)
    execv("/proc/self/exe", argv);
  // No restart (no /proc, say): run on as before, with the environment as the user gave it.
  restore(original);
  unsetenv(marker);
  huge_pages_status() = "ordinary pages (the restart with glibc.malloc.hugetlb=1 failed)";
#else
  (void)argv;
  huge_pages_status() = "ordinary pages (needs Linux and glibc 2.35 or later)";
#endif
}

}  // namespace shapestruct::cli
