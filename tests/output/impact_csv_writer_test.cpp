#include <gtest/gtest.h>

#include <charconv>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "output/impact_csv_writer.h"

namespace peensim {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> kNames = {"gear", "rod", "chamber wall"};

std::vector<ImpactRecord> random_impacts(std::size_t n, std::uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> any(-10.0, 10.0);
    std::uniform_real_distribution<double> tiny(-1e-300, 1e-300);
    std::vector<ImpactRecord> impacts(n);
    for (std::size_t i = 0; i < n; ++i) {
        auto& r = impacts[i];
        r.time_s = 1e-7 * static_cast<double>(i) + 1e-9 / 3.0;
        r.shot = static_cast<std::int32_t>(rng() % 100000);
        r.component = static_cast<std::int32_t>(i % kNames.size());
        r.triangle = static_cast<std::int32_t>(rng() % 5000000);
        r.point_m = Vec3(any(rng) * 1e-3, any(rng), i % 7 == 0 ? tiny(rng) : any(rng));
        r.v_in_m_per_s = Vec3(any(rng), any(rng), any(rng));
        r.vn_in_m_per_s = std::abs(any(rng));
        r.vt_in_m_per_s = i % 5 == 0 ? 0.0 : std::abs(any(rng));
        r.v_out_m_per_s = Vec3(any(rng), -0.0, any(rng) / 3.0);
        r.vn_out_m_per_s = std::abs(any(rng)) * 0.7;
    }
    impacts[0].shot = -2147483647 - 1;
    impacts[1].triangle = 2147483647;
    return impacts;
}

std::string read_file(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

std::vector<std::string> split(const std::string& line, char sep) {
    std::vector<std::string> fields;
    std::string field;
    std::istringstream in(line);
    while (std::getline(in, field, sep)) fields.push_back(field);
    return fields;
}

double to_double(const std::string& text) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    EXPECT_TRUE(ec == std::errc() && end == text.data() + text.size()) << text;
    return v;
}

// Bitwise equality: -0.0 must come back as -0.0.
void expect_same(double a, double b) { EXPECT_TRUE(std::signbit(a) == std::signbit(b) && a == b) << a << " vs " << b; }

class ImpactCsvWriterTest : public ::testing::Test {
protected:
    void SetUp() override {
        std::string pattern = (fs::temp_directory_path() / "peensim-csv-XXXXXX").string();
        ASSERT_NE(::mkdtemp(pattern.data()), nullptr);
        dir_ = pattern;
    }
    void TearDown() override { fs::remove_all(dir_); }

    fs::path final_path() const { return dir_ / "impacts.csv"; }
    fs::path partial_path() const { return dir_ / "impacts.csv.partial"; }

    // The file an uninterrupted run writes for `impacts`, in its own directory.
    std::string uninterrupted_file(const std::vector<ImpactRecord>& impacts) {
        const fs::path other = dir_ / "uninterrupted";
        fs::create_directory(other);
        ImpactCsvWriter writer(other.string(), kNames);
        writer.write(impacts);
        writer.finish();
        return read_file(other / "impacts.csv");
    }

    fs::path dir_;
};

TEST_F(ImpactCsvWriterTest, ValuesRoundTripExactly) {
    // More rows than fit in one buffer, so the buffer is flushed mid-run.
    const auto impacts = random_impacts(12000, 1);
    ImpactCsvWriter writer(dir_.string(), kNames);
    writer.write(impacts);
    EXPECT_EQ(writer.rows_written(), impacts.size());
    writer.finish();
    EXPECT_TRUE(writer.finished());

    EXPECT_FALSE(fs::exists(partial_path()));
    const std::string text = read_file(final_path());
    EXPECT_EQ(writer.bytes_written(), text.size());
    std::istringstream lines(text);
    std::string line;
    ASSERT_TRUE(std::getline(lines, line));
    EXPECT_EQ(line,
              "time_s,shot,component,triangle,x_m,y_m,z_m,vx_in_mps,vy_in_mps,vz_in_mps,"
              "vn_in_mps,vt_in_mps,vx_out_mps,vy_out_mps,vz_out_mps,vn_out_mps");
    EXPECT_EQ(line, kImpactCsvHeader);

    std::size_t row = 0;
    while (std::getline(lines, line)) {
        ASSERT_LT(row, impacts.size());
        const auto& r = impacts[row];
        const auto f = split(line, ',');
        ASSERT_EQ(f.size(), 16u) << line;
        expect_same(to_double(f[0]), r.time_s);
        EXPECT_EQ(std::stol(f[1]), r.shot);
        EXPECT_EQ(f[2], kNames[static_cast<std::size_t>(r.component)]);
        EXPECT_EQ(std::stol(f[3]), r.triangle);
        for (int k = 0; k < 3; ++k) {
            expect_same(to_double(f[4 + k]), r.point_m[k]);
            expect_same(to_double(f[7 + k]), r.v_in_m_per_s[k]);
            expect_same(to_double(f[12 + k]), r.v_out_m_per_s[k]);
        }
        expect_same(to_double(f[10]), r.vn_in_m_per_s);
        expect_same(to_double(f[11]), r.vt_in_m_per_s);
        expect_same(to_double(f[15]), r.vn_out_m_per_s);
        ++row;
    }
    EXPECT_EQ(row, impacts.size());
}

TEST_F(ImpactCsvWriterTest, ShortestFormIsUsed) {
    ImpactRecord r;
    r.time_s = 0.1;
    r.shot = 7;
    r.component = 1;
    r.triangle = 42;
    r.point_m = Vec3(1.0, 0.5, -2.5e-3);
    r.v_in_m_per_s = Vec3(0.0, 0.0, -3.0);
    r.vn_in_m_per_s = 3.0;
    r.vt_in_m_per_s = 0.0;
    r.v_out_m_per_s = Vec3(0.0, 0.0, 2.1);
    r.vn_out_m_per_s = 2.1;
    ImpactCsvWriter writer(dir_.string(), kNames);
    writer.write(r);
    writer.finish();
    EXPECT_EQ(read_file(final_path()), std::string(kImpactCsvHeader) + "\n0.1,7,rod,42,1,0.5,-0.0025,0,0,-3,3,0,0,0,2.1,2.1\n");
}

TEST_F(ImpactCsvWriterTest, NamesWithCommasAreQuoted) {
    ImpactRecord r;
    r.component = 0;
    ImpactCsvWriter writer(dir_.string(), {"left, \"top\" gear"});
    writer.write(r);
    writer.finish();
    const std::string text = read_file(final_path());
    EXPECT_NE(text.find("\n0,0,\"left, \"\"top\"\" gear\",0,"), std::string::npos) << text;
}

TEST_F(ImpactCsvWriterTest, UnknownComponentIndexThrows) {
    ImpactCsvWriter writer(dir_.string(), kNames);
    ImpactRecord r;
    r.component = 3;
    EXPECT_THROW(writer.write(r), std::out_of_range);
    r.component = -1;
    EXPECT_THROW(writer.write(r), std::out_of_range);
    EXPECT_EQ(writer.rows_written(), 0u);
}

TEST_F(ImpactCsvWriterTest, WriterDestroyedWithoutFinishLeavesOnlyThePartial) {
    const auto impacts = random_impacts(100, 2);
    {
        ImpactCsvWriter writer(dir_.string(), kNames);
        writer.write(impacts);
    }
    EXPECT_FALSE(fs::exists(final_path()));
    ASSERT_TRUE(fs::exists(partial_path()));
    // What it holds is exactly the finished file's content, up to where it stopped.
    EXPECT_EQ(read_file(partial_path()), uninterrupted_file(impacts));
}

TEST_F(ImpactCsvWriterTest, NewRunRemovesAStaleFinishedFile) {
    std::ofstream(final_path()) << "old run\n";
    ImpactCsvWriter writer(dir_.string(), kNames);
    EXPECT_FALSE(fs::exists(final_path()));
    EXPECT_TRUE(fs::exists(partial_path()));
}

TEST_F(ImpactCsvWriterTest, ResumeTruncatesToTheCheckpointAndMatchesAnUninterruptedRun) {
    const auto impacts = random_impacts(5000, 3);
    const std::size_t at_checkpoint = 2000;
    const std::size_t at_kill = 3100;
    std::uint64_t checkpoint_bytes = 0;
    std::uint64_t checkpoint_rows = 0;
    {
        ImpactCsvWriter writer(dir_.string(), kNames);
        for (std::size_t i = 0; i < at_checkpoint; ++i) writer.write(impacts[i]);
        writer.flush_durable();
        checkpoint_bytes = writer.bytes_written();
        checkpoint_rows = writer.rows_written();
        EXPECT_EQ(fs::file_size(partial_path()), checkpoint_bytes);
        // Rows after the checkpoint reach the file, then the run is "killed".
        for (std::size_t i = at_checkpoint; i < at_kill; ++i) writer.write(impacts[i]);
    }
    ASSERT_GT(fs::file_size(partial_path()), checkpoint_bytes);

    auto writer = ImpactCsvWriter::resume(dir_.string(), kNames, checkpoint_bytes, checkpoint_rows);
    EXPECT_EQ(fs::file_size(partial_path()), checkpoint_bytes);
    EXPECT_EQ(writer.rows_written(), at_checkpoint);
    for (std::size_t i = at_checkpoint; i < impacts.size(); ++i) writer.write(impacts[i]);
    EXPECT_EQ(writer.rows_written(), impacts.size());
    writer.finish();

    const std::string resumed = read_file(final_path());
    EXPECT_EQ(writer.bytes_written(), resumed.size());
    EXPECT_TRUE(resumed == uninterrupted_file(impacts)) << "resumed file differs";
}

TEST_F(ImpactCsvWriterTest, ResumeFailsClearly) {
    auto expect_error = [&](std::uint64_t bytes, const std::string& needle) {
        try {
            ImpactCsvWriter::resume(dir_.string(), kNames, bytes, 0);
            FAIL() << "expected an error for " << needle;
        } catch (const std::runtime_error& e) {
            EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
        }
    };
    expect_error(100, "No such file or directory");  // no .partial at all

    std::uint64_t full = 0;
    {
        ImpactCsvWriter writer(dir_.string(), kNames);
        writer.write(random_impacts(3, 4));
        writer.flush_durable();
        full = writer.bytes_written();
    }
    expect_error(full + 1, "the checkpoint recorded");  // shorter than the checkpoint
    expect_error(full - 1, "no row end");               // inside a row
    expect_error(kImpactCsvHeader.size(), "header");    // inside the header line
    EXPECT_EQ(fs::file_size(partial_path()), full);     // failed resumes change nothing

    std::ofstream(partial_path(), std::ios::trunc) << "not,an,impacts,file\n";
    expect_error(20, "header");
}

TEST_F(ImpactCsvWriterTest, MisuseAfterFinishThrows) {
    ImpactCsvWriter writer(dir_.string(), kNames);
    writer.finish();
    EXPECT_THROW(writer.write(ImpactRecord{}), std::logic_error);
    EXPECT_THROW(writer.finish(), std::logic_error);
    EXPECT_EQ(read_file(final_path()), std::string(kImpactCsvHeader) + "\n");
}

TEST_F(ImpactCsvWriterTest, MissingDirectoryIsAnError) {
    EXPECT_THROW(ImpactCsvWriter((dir_ / "missing").string(), kNames), std::runtime_error);
}

}  // namespace
}  // namespace peensim
