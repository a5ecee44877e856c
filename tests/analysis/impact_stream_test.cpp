// The impact stream hands over, in blocks read on a second thread, exactly the rows the reader
// gives, in order, with their component indices; it runs the reader-side work once per named
// row, rethrows the reader's errors on the consumer's thread and stops cleanly when abandoned.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <thread>

#include "analysis/impact_log_reader.h"
#include "analysis/impact_stream.h"
#include "output/impact_csv_writer.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

// Spans several blocks of the stream (8192 rows each) and ends inside one.
constexpr int kRows = 30001;

std::string write_stream_log(const fs::path& dir, int rows) {
    ImpactCsvWriter w(dir.string(), {"gear", "chamber", "axle"});
    for (int k = 0; k < rows; ++k) {
        ImpactRecord r;
        r.time_s = 1e-4 * k;
        r.shot = k;
        r.component = k % 3;
        r.triangle = k;
        r.point_m = Vec3(k, 0, 0);
        r.vn_in_m_per_s = 1.0 + k;
        w.write(r);
    }
    w.finish();
    return (dir / "impacts.csv").string();
}

}  // namespace

TEST(ImpactStream, DeliversEveryRowInOrderWithComponentIndices) {
    TempDir dir;
    const std::string path = write_stream_log(dir.path, kRows);
    int reader_side_rows = 0;
    std::thread::id reader_thread;
    // "axle" is not asked for: its rows come with component -1 and skip the reader-side work.
    ImpactStream stream(path, {"chamber", "gear"}, [&](const ImpactRow& row, int component) {
        EXPECT_EQ(component, row.shot % 3 == 0 ? 1 : 0);
        ++reader_side_rows;
        reader_thread = std::this_thread::get_id();
    });
    int k = 0;
    for (auto block = stream.next_block(); !block.empty(); block = stream.next_block()) {
        for (const IndexedImpact& impact : block) {
            EXPECT_EQ(impact.row.shot, k);
            EXPECT_EQ(impact.row.time_s, 1e-4 * k);
            EXPECT_EQ(impact.row.vn_in_m_per_s, 1.0 + k);
            EXPECT_EQ(impact.component, k % 3 == 0 ? 1 : k % 3 == 1 ? 0 : -1);
            ++k;
        }
    }
    EXPECT_EQ(k, kRows);
    EXPECT_EQ(stream.rows(), static_cast<std::uint64_t>(kRows));
    EXPECT_FALSE(stream.truncated());
    EXPECT_EQ(reader_side_rows, 20001);  // rows of gear and chamber: all but every third-plus-two
    EXPECT_NE(reader_thread, std::this_thread::get_id());
    EXPECT_TRUE(stream.next_block().empty());  // and stays at the end
}

TEST(ImpactStream, ADamagedRowIsRethrownAfterTheRowsBeforeIt) {
    TempDir dir;
    const std::string path = write_stream_log(dir.path, kRows);
    { std::ofstream(path, std::ios::app) << "0.5,1,gear,oops\n"; }
    ImpactStream stream(path, {"gear"});
    int rows = 0;
    try {
        for (auto block = stream.next_block(); !block.empty(); block = stream.next_block()) rows += static_cast<int>(block.size());
        FAIL() << "a damaged row must be refused";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ":" + std::to_string(kRows + 2) + ":"), std::string::npos) << e.what();
    }
    EXPECT_EQ(rows, kRows);
}

TEST(ImpactStream, ATruncatedLogIsSaidAndAnAbandonedStreamStops) {
    TempDir dir;
    const std::string path = write_stream_log(dir.path, kRows);
    {
        std::ofstream(path, std::ios::app) << "0.5,1,ge";  // a run killed mid-write
    }
    {
        ImpactStream stream(path, {"gear"});
        int rows = 0;
        for (auto block = stream.next_block(); !block.empty(); block = stream.next_block()) rows += static_cast<int>(block.size());
        EXPECT_EQ(rows, kRows);
        EXPECT_TRUE(stream.truncated());
    }
    // Destroyed after one block, with the reader thread blocked on a full ring: no hang.
    ImpactStream abandoned(path, {"gear"});
    EXPECT_FALSE(abandoned.next_block().empty());
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
}

TEST(ImpactStream, AMissingLogThrowsOnTheCallersThread) {
    TempDir dir;
    EXPECT_THROW(ImpactStream((dir.path / "missing.csv").string(), {"gear"}), std::runtime_error);
}
