// The impact log reader streams what the writer wrote, exactly, and says clearly what is wrong
// with an empty, foreign, truncated or damaged log.
#include <gtest/gtest.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "analysis/impact_log_reader.h"
#include "common/input_error.h"
#include "output/impact_csv_writer.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;
using peensim::testing::TempDir;
using namespace peensim;

namespace {

ImpactRecord record(int k) {
    ImpactRecord r;
    r.time_s = 1e-3 * k + 1.0 / 3.0;
    r.shot = k % 97;
    r.component = k % 2;
    r.triangle = 7 * k;
    r.point_m = Vec3(0.1 / (k + 1), -2e-3 * k, 1.0 / 7.0);
    r.v_in_m_per_s = Vec3(k * 0.25, -1.0 / 3.0, 3.0);
    r.vn_in_m_per_s = 3.0 + k * 1e-9;
    r.vt_in_m_per_s = 0.1 * k;
    r.v_out_m_per_s = Vec3(-0.5, 2.0 / 3.0, -1.5);
    r.vn_out_m_per_s = 1.5;
    return r;
}

std::string write_log(const fs::path& dir, int rows) {
    ImpactCsvWriter w(dir.string(), {"gear", "chamber"});
    for (int k = 0; k < rows; ++k) w.write(record(k));
    w.finish();
    return (dir / "impacts.csv").string();
}

}  // namespace

TEST(ImpactLogReader, ReadsBackExactlyWhatWasWritten) {
    TempDir dir;
    const std::string path = write_log(dir.path, 1000);
    ImpactLogReader reader(path);
    ImpactRow row;
    int k = 0;
    while (reader.next(row)) {
        const ImpactRecord r = record(k);
        EXPECT_EQ(row.time_s, r.time_s);
        EXPECT_EQ(row.shot, r.shot);
        EXPECT_EQ(row.component, k % 2 ? "chamber" : "gear");
        EXPECT_EQ(row.triangle, r.triangle);
        EXPECT_EQ(row.point_m, r.point_m);
        EXPECT_EQ(row.v_in_m_per_s, r.v_in_m_per_s);
        EXPECT_EQ(row.vn_in_m_per_s, r.vn_in_m_per_s);
        EXPECT_EQ(row.vt_in_m_per_s, r.vt_in_m_per_s);
        EXPECT_EQ(row.v_out_m_per_s, r.v_out_m_per_s);
        EXPECT_EQ(row.vn_out_m_per_s, r.vn_out_m_per_s);
        ++k;
    }
    EXPECT_EQ(k, 1000);
    EXPECT_EQ(reader.rows(), 1000u);
    EXPECT_FALSE(reader.truncated());
}

TEST(ImpactLogReader, ALogCutMidLineGivesTheCompleteRowsAndSaysSo) {
    TempDir dir;
    const std::string path = write_log(dir.path, 100);
    const auto size = fs::file_size(path);
    fs::resize_file(path, size - 17);  // a run killed while writing its last row
    ImpactLogReader reader(path);
    ImpactRow row;
    std::uint64_t n = 0;
    while (reader.next(row)) ++n;
    EXPECT_EQ(n, 99u);
    EXPECT_TRUE(reader.truncated());
    EXPECT_EQ(reader.truncated_line(), 101u);  // the header, 99 rows, then the cut one
}

// NaN and infinity parse as numbers, but the writer logs only finite values: such a row is damage,
// refused at its line and column with the column's name (it was dropped in silence: the analysis'
// window test `time >= from` is false for NaN).
TEST(ImpactLogReader, NonFiniteAndGarbageFieldsNameTheirLineAndColumn) {
    TempDir dir;
    const std::string path = write_log(dir.path, 10);
    std::string text;
    {
        std::ifstream in(path);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto refused = [&](const std::string& row, const std::string& phrase) {
        const auto second = text.find('\n', text.find('\n') + 1);  // end of line 2 (row 1)
        std::ofstream(path, std::ios::trunc) << text.substr(0, second + 1) + row + "\n" + text.substr(second + 1);
        ImpactLogReader reader(path);
        ImpactRow r;
        try {
            while (reader.next(r)) {}
            ADD_FAILURE() << "accepted: " << row;
        } catch (const InputError& e) {
            EXPECT_NE(std::string(e.what()).find(phrase), std::string::npos) << e.what();
        }
    };
    refused("nan,1,gear,0,0,0,0,0,0,0,0,0,0,0,0,0", path + ":3:1: time_s: malformed impact row 2: expected a finite number, got 'nan'");
    refused("0.5,1,gear,0,0,0,0,0,0,0,inf,0,0,0,0,0",
            path + ":3:26: vn_in_mps: malformed impact row 2: expected a finite number, got 'inf'");
    refused("0.5,1,gear,x,0,0,0,0,0,0,1,0,0,0,0,0", ":3:12: triangle: malformed impact row 2: expected an integer, got 'x'");
    refused("0.5,1,gear,0,0", ":3:15: y_m: malformed impact row 2: expected more fields");
    refused("0.5,1,gear,0,0,0,0,0,0,0,1,0,0,0,0,0,7", ":3:38: malformed impact row 2: expected 16 fields, got more");
    refused(std::string("0.5,1,ge\x00"
                        "ar",
                        11),
            ":3: malformed impact row 2: expected a text row, got binary data '0.5,1,ge\\x00ar'");
}

TEST(ImpactLogReader, EmptyForeignAndDamagedLogsAreClearErrors) {
    TempDir dir;
    const fs::path empty = dir.path / "empty.csv";
    std::ofstream(empty).close();
    try {
        ImpactLogReader r(empty.string());
        FAIL() << "an empty log must be refused";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("empty"), std::string::npos) << e.what();
    }
    const fs::path foreign = dir.path / "foreign.csv";
    std::ofstream(foreign) << "a,b,c\n1,2,3\n";
    try {
        ImpactLogReader r(foreign.string());
        FAIL() << "a foreign CSV must be refused";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("not a peensim impact log"), std::string::npos) << e.what();
    }
    try {
        ImpactLogReader r((dir.path / "missing.csv").string());
        FAIL() << "a missing log must be refused";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("cannot open"), std::string::npos) << e.what();
    }
    // A damaged row in the middle: file and line named.
    const std::string path = write_log(dir.path, 10);
    std::string text;
    {
        std::ifstream in(path);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    const auto third = text.find('\n', text.find('\n', text.find('\n') + 1) + 1);  // end of row 2 (line 3)
    text.insert(third + 1, "0.5,1,gear,oops\n");
    std::ofstream(path) << text;
    ImpactLogReader reader(path);
    ImpactRow row;
    try {
        while (reader.next(row)) {}
        FAIL() << "a damaged row must be refused";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find(path + ":4:"), std::string::npos) << e.what();
    }
}

TEST(ImpactLogReader, StreamsFast) {
    TempDir dir;
    const std::string path = write_log(dir.path, 200000);
    const auto t0 = std::chrono::steady_clock::now();
    ImpactLogReader reader(path);
    ImpactRow row;
    double sum = 0.0;
    while (reader.next(row)) sum += row.vn_in_m_per_s;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::cout << "[ reader   ] " << reader.rows() << " rows (" << fs::file_size(path) / 1e6 << " MB) in " << s
              << " s: " << reader.rows() / s / 1e6 << " M rows/s\n";
    EXPECT_EQ(reader.rows(), 200000u);
    EXPECT_GT(sum, 0.0);
}
