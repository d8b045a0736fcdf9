// A short soak of the robot link in CI (the long one is soak_link, docs/robot-link.md "Soak"):
// 2,000 loopback requests after a warm-up of 2,000, a mix of valid and malformed JSON lines and
// binary messages from four clients at once, clients leaving mid-message and a burst of 100
// clients beyond the limit of 32. Every answer must decode, echo its request's id and carry a
// status that request can have; the resident memory must stay within 5 % of its value after the
// warm-up.
#include "tests/support/LinkSoak.h"

#include <cstdio>
#include <gtest/gtest.h>

// AddressSanitizer keeps freed memory in quarantine: resident memory then grows with every
// request and says nothing about the server.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitized = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kSanitized = true;
#else
constexpr bool kSanitized = false;
#endif
#else
constexpr bool kSanitized = false;
#endif

TEST(RobotLinkSoak, ShortSoakAnswersEveryRequestWellAndKeepsMemoryFlat) {
  scanpick::test::SoakOptions o;
  o.requests = 2000;
  o.warmup = 2000;
  o.bursts = 1;
  const scanpick::test::SoakReport r = scanpick::test::runLinkSoak(o);
  std::printf("short soak: %ld requests in %.1f s, RSS %ld kB -> %ld kB (%+.2f %%)\n", r.requests,
              r.seconds, r.rss_warm_kb, r.rss_end_kb, r.growthPercent());
  for (const auto& p : r.problems)
    ADD_FAILURE() << "unexpected answer: " << p;
  // 2,000 requests of the mix and one burst of 100 clients, one request each.
  EXPECT_EQ(r.requests, 2100);
  EXPECT_EQ(r.unexpected, 0);
  EXPECT_EQ(r.well_formed, r.answers);
  EXPECT_GE(r.burst_refused,
            100 - 32 - 4); // beyond the limit of 32 (4 soak clients may hold slots)
  ASSERT_GT(r.rss_warm_kb, 0) << "/proc/self/status has no VmRSS";
  if (kSanitized)
    GTEST_SKIP() << "memory growth not checked under AddressSanitizer (its quarantine grows)";
  EXPECT_LE(r.growthPercent(), 5.0);
}
