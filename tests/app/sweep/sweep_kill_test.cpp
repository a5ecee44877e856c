// A sweep killed outright (SIGKILL: it cannot pass anything on to its runs), or one rank of an MPI
// sweep killed: its `peensim run` children die with it (PR_SET_PDEATHSIG, app/sweep/sweep_book.h) instead
// of running on, holding their directories' locks; the same command run again at once resumes
// every run without "in use" and without a retry.
#include <gtest/gtest.h>

#include <signal.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "app/run/run_job.h"
#include "support/child_process.h"
#include "support/files.h"
#include "support/mpirun_environment.h"
#include "support/shipped_scenes.h"
#include "support/temp_dir.h"

namespace fs = std::filesystem;

namespace peensim::testing {
namespace {

// A process seen in /proc: its pid and start time (a pid reused later is another process).
struct Process {
    int pid = 0;
    std::string start;
};

// Fields of /proc/<pid>/stat after the command name: [0] state, [1] ppid, ..., [19] start time.
std::vector<std::string> stat_fields(int pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::string> fields;
    const std::size_t close = text.rfind(')');
    if (close == std::string::npos) return fields;
    std::istringstream rest(text.substr(close + 1));
    for (std::string f; rest >> f;) fields.push_back(f);
    return fields;
}

std::string command_line(int pid) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/cmdline", std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    for (char& c : text)
        if (c == '\0') c = ' ';
    return text;
}

// The `peensim run` children of `parent`.
std::vector<Process> runs_of(int parent) {
    std::vector<Process> found;
    for (const auto& entry : fs::directory_iterator("/proc")) {
        const std::string name = entry.path().filename().string();
        if (name.find_first_not_of("0123456789") != std::string::npos) continue;
        const int pid = std::stoi(name);
        const std::vector<std::string> f = stat_fields(pid);
        if (f.size() < 20 || std::stoi(f[1]) != parent) continue;
        if (command_line(pid).find(" run ") != std::string::npos) found.push_back({pid, f[19]});
    }
    return found;
}

bool alive(const Process& p) {
    const std::vector<std::string> f = stat_fields(p.pid);
    return f.size() >= 20 && f[19] == p.start && f[0] != "Z" && f[0] != "X";
}

// Waits up to `limit_s` for `done`; whether it came.
template <class Done>
bool wait_for(double limit_s, Done&& done) {
    const auto t0 = std::chrono::steady_clock::now();
    while (!done()) {
        if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > limit_s) return false;
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    return true;
}

std::vector<std::string> sweep_args(const fs::path& out) {
    return {PEENSIM_BINARY,
            "sweep",
            kRod,
            "-o",
            out.string(),
            "--vary",
            "shot.count=256,512",
            "--set",
            "process.duration=1 s",
            "--set",
            "output.checkpoint_interval=0.05 s",
            "--jobs",
            "2"};
}

// Every log of the sweep's runs, and what it printed.
std::string everything_said(const fs::path& out, const fs::path& dir) {
    std::string said = read_file(dir / "rerun.out") + read_file(dir / "rerun.err");
    if (fs::exists(out / "sweep" / "logs"))
        for (const auto& log : fs::directory_iterator(out / "sweep" / "logs")) said += read_file(log.path());
    return said;
}

// The rerun after the kill: it resumes both runs at once (none "in use", none retried) and finishes.
void expect_rerun_resumes(const fs::path& out, const fs::path& dir) {
    ChildProcess rerun(sweep_args(out), (dir / "rerun.out").string(), (dir / "rerun.err").string());
    ASSERT_EQ(rerun.wait_exit(300.0), std::optional<int>(kExitOk)) << everything_said(out, dir);
    const std::string said = everything_said(out, dir);
    EXPECT_EQ(said.find("in use"), std::string::npos) << said;
    EXPECT_EQ(said.find("trying it once more"), std::string::npos) << said;
    for (const char* run : {"count-256/s0", "count-512/s0"}) EXPECT_TRUE(fs::exists(out / run / "impacts.csv")) << run;
}

TEST(SweepKill, ASweepKilledOutrightTakesItsRunsWithItAndTheRerunResumesAtOnce) {
    TempDir dir;
    const fs::path out = dir.path / "out";
    ChildProcess sweep(sweep_args(out), (dir.path / "sweep.out").string(), (dir.path / "sweep.err").string());
    // Both runs under way, each with a checkpoint to resume from.
    ASSERT_TRUE(wait_for(120.0, [&] {
        return fs::exists(out / "count-256" / "s0" / "checkpoint.bin") && fs::exists(out / "count-512" / "s0" / "checkpoint.bin");
    })) << read_file(dir.path / "sweep.err");
    const std::vector<Process> runs = runs_of(sweep.pid());
    ASSERT_EQ(runs.size(), 2u) << "the sweep's runs were not both running";
    sweep.signal(SIGKILL);
    ASSERT_EQ(sweep.wait_exit(10.0), std::nullopt);  // killed: no exit code
    EXPECT_TRUE(wait_for(5.0, [&] { return !alive(runs[0]) && !alive(runs[1]); })) << "a run outlived its sweep by 5 s";
    expect_rerun_resumes(out, dir.path);
}

// The rank of an MPI sweep (`mpirun -n 2 peensim sweep ...`) that is not rank 0, found by its environment.
int rank_one_of(int mpirun) {
    std::vector<int> pending{mpirun};
    while (!pending.empty()) {  // mpirun's descendants (it may start the ranks through a daemon)
        const int parent = pending.back();
        pending.pop_back();
        for (const auto& entry : fs::directory_iterator("/proc")) {
            const std::string name = entry.path().filename().string();
            if (name.find_first_not_of("0123456789") != std::string::npos) continue;
            const int pid = std::stoi(name);
            const std::vector<std::string> f = stat_fields(pid);
            if (f.size() < 2 || std::stoi(f[1]) != parent) continue;
            std::ifstream in("/proc/" + name + "/environ", std::ios::binary);
            const std::string environment((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
            if (environment.find(std::string("OMPI_COMM_WORLD_RANK=1") + '\0') != std::string::npos &&
                command_line(pid).find(" sweep ") != std::string::npos)
                return pid;
            pending.push_back(pid);
        }
    }
    return 0;
}

TEST(SweepKill, AnMpiRankKilledTakesItsRunWithItAndTheRerunResumesAtOnce) {
    const std::string mpirun = "/usr/bin/mpirun";
    ASSERT_TRUE(fs::exists(mpirun)) << "mpirun not found: .ci/install-deps installs openmpi-bin";
    mpirun_environment();
    TempDir dir;
    const fs::path out = dir.path / "out";
    std::vector<std::string> args{mpirun, "-n", "2", "--oversubscribe"};
    for (const std::string& a : sweep_args(out)) args.push_back(a);
    args.back() = "1";  // --jobs 1: one run on each rank
    ChildProcess mpi(args, (dir.path / "mpi.out").string(), (dir.path / "mpi.err").string());
    ASSERT_TRUE(wait_for(120.0, [&] {
        return fs::exists(out / "count-256" / "s0" / "checkpoint.bin") && fs::exists(out / "count-512" / "s0" / "checkpoint.bin");
    })) << read_file(dir.path / "mpi.err");
    const int rank_one = rank_one_of(mpi.pid());
    ASSERT_GT(rank_one, 0) << "rank 1 not found";
    const std::vector<Process> its_runs = runs_of(rank_one);
    ASSERT_EQ(its_runs.size(), 1u);
    ::kill(rank_one, SIGKILL);
    EXPECT_TRUE(wait_for(5.0, [&] { return !alive(its_runs[0]); })) << "rank 1's run outlived it by 5 s";
    // Open MPI ends the whole job when a rank dies (rank 0 and its run with it).
    EXPECT_TRUE(mpi.wait_exit(60.0).has_value()) << "mpirun went on after a rank died";
    expect_rerun_resumes(out, dir.path);
}

}  // namespace
}  // namespace peensim::testing
