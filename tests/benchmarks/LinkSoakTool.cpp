// soak_link: the robot link's soak (a day of requests simulated as 100,000, resident memory within
// 5 %; docs/robot-link.md, "Soak"). Not run in CI (it takes minutes);
// RobotLinkSoakTest runs a short version. Prints the requests, the time, the resident memory after
// the warm-up and at the end, and exits 1 when an answer was wrong or the memory grew by more than
// 5 %.
//
//   soak_link [--requests 100000] [--warmup 2000] [--clients 4] [--bursts 4] [--seed 43]
#include "tests/support/LinkSoak.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

int main(int argc, char** argv) {
  scanpick::test::SoakOptions o;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc || arg.rfind("--", 0) != 0) {
      std::fprintf(stderr,
                   "usage: soak_link [--requests N] [--warmup N] [--clients N] [--bursts N] "
                   "[--seed N]\n");
      return 2;
    }
    const long value = std::strtol(argv[++i], nullptr, 10);
    if (arg == "--requests")
      o.requests = value;
    else if (arg == "--warmup")
      o.warmup = value;
    else if (arg == "--clients")
      o.clients = int(value);
    else if (arg == "--bursts")
      o.bursts = int(value);
    else if (arg == "--seed")
      o.seed = std::uint64_t(value);
    else {
      std::fprintf(stderr, "soak_link: unknown option %s\n", arg.c_str());
      return 2;
    }
  }
  if (o.requests < 1 || o.warmup < 0 || o.clients < 1 || o.bursts < 0) {
    std::fprintf(stderr, "soak_link: --requests and --clients must be positive\n");
    return 2;
  }
  o.log = [](const std::string& line) {
    std::printf("  %s\n", line.c_str());
    std::fflush(stdout);
  };
  std::printf("soak_link: %ld requests after a warm-up of %ld, %d client(s) at once, %d burst(s) "
              "of %d clients\n",
              o.requests, o.warmup, o.clients, o.bursts, o.burst_clients);
  const scanpick::test::SoakReport r = scanpick::test::runLinkSoak(o);
  std::printf("requests %ld (bursts included) in %.1f s (%.0f/s); answers %ld, well-formed and "
              "expected %ld, unexpected %ld\n",
              r.requests, r.seconds, double(r.requests) / r.seconds, r.answers, r.well_formed,
              r.unexpected);
  std::printf("bursts: %ld clients, %ld refused (too many clients)\n", r.burst_clients,
              r.burst_refused);
  std::printf("server: %llu connections (%llu refused), %llu requests answered, %llu error "
              "answers, %llu busy, %llu timeouts\n",
              static_cast<unsigned long long>(r.stats.accepted),
              static_cast<unsigned long long>(r.stats.refused),
              static_cast<unsigned long long>(r.stats.requests),
              static_cast<unsigned long long>(r.stats.errors),
              static_cast<unsigned long long>(r.stats.busy),
              static_cast<unsigned long long>(r.stats.timeouts));
  std::printf("RSS after warm-up %ld kB, at the end %ld kB (%+.2f %%), highest sample %ld kB\n",
              r.rss_warm_kb, r.rss_end_kb, r.growthPercent(), r.rss_max_kb);
  for (const auto& p : r.problems)
    std::printf("unexpected: %s\n", p.c_str());
  const bool pass = r.unexpected == 0 && r.well_formed == r.answers && r.growthPercent() <= 5.0;
  std::printf("%s\n", pass ? "PASS" : "FAIL");
  return pass ? 0 : 1;
}
