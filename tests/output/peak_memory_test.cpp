#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>
#include <vector>

#include "output/peak_memory.h"

namespace peensim {
namespace {

// bytes, a "VmHWM:" (peak) or "VmRSS:" (current) line of /proc/self/status (given in kB).
std::uint64_t proc_status_bytes(const std::string& key) {
    std::ifstream status("/proc/self/status");
    std::string word;
    while (status >> word) {
        if (word == key) {
            std::uint64_t kib = 0;
            status >> kib;
            return kib * 1024u;
        }
    }
    return 0;
}

TEST(PeakMemoryTest, MatchesTheKernelHighWaterMark) {
    const std::uint64_t hwm_before = proc_status_bytes("VmHWM:");
    const std::uint64_t peak = peak_resident_bytes();
    const std::uint64_t hwm_after = proc_status_bytes("VmHWM:");
    ASSERT_GT(hwm_before, 0u);
    EXPECT_GT(peak, 1024u * 1024u);  // any process maps more than 1 MiB
    // The kernel's per-thread rss counters lag by a few pages: allow 1 MiB either way.
    const std::uint64_t slack = std::uint64_t{1} << 20;
    EXPECT_GE(peak + slack, hwm_before);
    EXPECT_LE(peak, hwm_after + slack);
}

TEST(PeakMemoryTest, GrowsWhenMoreMemoryIsTouched) {
    const std::uint64_t before = peak_resident_bytes();
    const std::uint64_t current = proc_status_bytes("VmRSS:");
    // Touch enough pages to lift the resident set 64 MiB above the earlier peak.
    const std::uint64_t extra = (before > current ? before - current : 0) + (std::uint64_t{64} << 20);
    std::vector<char> block(static_cast<std::size_t>(extra), 1);
    volatile char sink = block[block.size() / 2];
    (void)sink;
    EXPECT_GE(peak_resident_bytes(), before + (std::uint64_t{32} << 20));
}

}  // namespace
}  // namespace peensim
