// `arbor sweep` and `arbor merge` end to end with the real binary on tiny simulated runs: a sweep killed
// with SIGKILL and restarted records exactly the rows of an uninterrupted one; three merged shards equal
// the unsharded sweep; a malformed spec fails before any run starts.
#include <signal.h>

#include <algorithm>
#include <chrono>
#include <map>
#include <set>
#include <thread>

#include <fmt/core.h>
#include <gtest/gtest.h>

#include "core/io/directory_lock.h"
#include "experiments/sweep/results_log.h"
#include "tests/experiments/sweep_test_util.h"

namespace arbor {
namespace {

using testing_util::arbor_binary;
using testing_util::read_text;
using testing_util::run_to_end;
using testing_util::ScratchDir;
using testing_util::write_text;

// 12 tiny runs (a few milliseconds of filtering each; the process start dominates).
const std::string& tiny_spec() {
  static const std::string spec = read_text(std::string(ARBOR_SOURCE_DIR) + "/tests/data/sweeps/tiny.toml");
  return spec;
}
constexpr std::size_t kTinyRuns = 12;

// The identity of a row: its parameters and status (not timings, hosts or finish times).
std::string tuple_of(const ResultRow& row) {
  std::string out;
  for (const char* c : {"key", "status", "dataset", "world", "world_landmarks", "world_steps", "clutter", "world_seed",
                        "filter", "map", "assoc", "particles", "seed", "threads"})
    out += std::string(c) + "=" + (row.contains(c) ? row[c].dump() : "?") + ";";
  return out;
}

// Rows of DIR as a multiset of tuples, after checking the files are whole: every line complete and parsed,
// the CSV holding the same number of rows as the JSONL.
std::multiset<std::string> rows_of(const std::string& dir) {
  const std::string jsonl = read_text(dir + "/results.jsonl");
  EXPECT_TRUE(jsonl.empty() || jsonl.back() == '\n') << "half row at the end of " << dir;
  const auto rows = read_result_rows(dir + "/results.jsonl");
  std::multiset<std::string> tuples;
  for (const auto& r : rows) tuples.insert(tuple_of(r));
  const std::string csv = read_text(dir + "/results.csv");
  EXPECT_EQ(static_cast<std::size_t>(std::count(csv.begin(), csv.end(), '\n')), rows.size() + 1) << "CSV rows != JSONL rows";
  return tuples;
}

std::size_t complete_lines(const std::string& path) {
  const std::string text = read_text(path);
  return static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
}

class SweepEndToEnd : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    binary_ = arbor_binary();
    if (binary_.empty()) return;
    scratch_ = new ScratchDir("sweep_e2e");
    write_text(*scratch_ / "tiny.toml", tiny_spec());
    reference_rc_ = run_to_end({binary_, "sweep", *scratch_ / "tiny.toml", "--out", *scratch_ / "reference", "--jobs", "2"},
                               *scratch_ / "reference.log");
  }
  static void TearDownTestSuite() {
    delete scratch_;
    scratch_ = nullptr;
  }
  void SetUp() override {
    if (binary_.empty()) GTEST_SKIP() << "ARBOR_BINARY_DIR/bin/arbor not found (run through ctest after building 'arbor')";
    ASSERT_EQ(reference_rc_, 0) << read_text(*scratch_ / "reference.log");
  }
  std::string spec() const { return *scratch_ / "tiny.toml"; }
  std::multiset<std::string> reference() const { return rows_of(*scratch_ / "reference"); }

  static inline std::string binary_;
  static inline ScratchDir* scratch_ = nullptr;
  static inline int reference_rc_ = -1;
};

TEST_F(SweepEndToEnd, UninterruptedSweepRecordsEveryRunOnceAndOk) {
  const auto rows = reference();
  EXPECT_EQ(rows.size(), kTinyRuns);
  EXPECT_EQ(std::set<std::string>(rows.begin(), rows.end()).size(), kTinyRuns);
  for (const auto& r : rows) EXPECT_NE(r.find("status=\"ok\""), std::string::npos) << r;
  // Rerunning the finished sweep runs nothing and changes nothing.
  const std::string before = read_text(*scratch_ / "reference/results.jsonl");
  ASSERT_EQ(run_to_end({binary_, "sweep", spec(), "--out", *scratch_ / "reference"}, *scratch_ / "again.log"), 0);
  EXPECT_EQ(read_text(*scratch_ / "reference/results.jsonl"), before);
}

TEST_F(SweepEndToEnd, KilledSweepResumesToExactlyTheUninterruptedRows) {
  ScratchDir dir("killed");
  const std::string out = dir / "out";
  const pid_t pid = start_child({binary_, "sweep", spec(), "--out", out, "--jobs", "2"}, dir / "first.log");
  // Kill as soon as the first row lands: runs are in flight, others not yet started.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (complete_lines(out + "/results.jsonl") < 1 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  ::kill(pid, SIGKILL);
  const ChildExit killed = wait_child(pid);
  EXPECT_EQ(killed.signal, SIGKILL) << "the sweep finished before it could be killed";
  const std::size_t rows_at_kill = complete_lines(out + "/results.jsonl");
  EXPECT_GE(rows_at_kill, 1u);
  EXPECT_LT(rows_at_kill, kTinyRuns) << "the kill did not land mid-sweep";
  // Power loss in the middle of an append would leave a row without its newline: add one by hand.
  {
    std::ofstream jsonl(out + "/results.jsonl", std::ios::app);
    jsonl << "{\"key\":\"uniform-n30-t25-c0.5__fastslam1-naive-known-m3-s1-t1\",\"stat";
  }
  ASSERT_EQ(run_to_end({binary_, "sweep", spec(), "--out", out, "--jobs", "2"}, dir / "second.log"), 0)
      << read_text(dir / "second.log");
  EXPECT_EQ(rows_of(out), reference());
  EXPECT_NE(read_text(dir / "second.log").find(fmt::format("{} already recorded", rows_at_kill)), std::string::npos)
      << read_text(dir / "second.log");
}

TEST_F(SweepEndToEnd, ThreeMergedShardsEqualTheUnshardedSweep) {
  ScratchDir dir("shards");
  std::vector<std::string> merge{binary_, "merge"};
  std::size_t total = 0;
  for (int i = 0; i < 3; ++i) {
    const std::string out = dir / ("shard" + std::to_string(i));
    ASSERT_EQ(run_to_end({binary_, "sweep", spec(), "--out", out, "--shard", fmt::format("{}/3", i)}, dir / "shard.log"), 0)
        << read_text(dir / "shard.log");
    total += rows_of(out).size();
    merge.push_back(out);
  }
  EXPECT_EQ(total, kTinyRuns);
  merge.push_back(dir / "shard0");  // a directory given twice: its rows are de-duplicated by key
  merge.insert(merge.end(), {"--out", dir / "merged"});
  ASSERT_EQ(run_to_end(merge, dir / "merge.log"), 0) << read_text(dir / "merge.log");
  EXPECT_EQ(rows_of(dir / "merged"), reference());
  // Merging in steps gives the same rows: a merge into an earlier merge keeps that merge's rows.
  ASSERT_EQ(run_to_end({binary_, "merge", dir / "shard0", dir / "shard1", "--out", dir / "stepwise"}, dir / "s1.log"), 0);
  ASSERT_EQ(run_to_end({binary_, "merge", dir / "shard2", "--out", dir / "stepwise"}, dir / "s2.log"), 0)
      << read_text(dir / "s2.log");
  EXPECT_EQ(rows_of(dir / "stepwise"), reference());
}

TEST_F(SweepEndToEnd, MergeRefusesShardsOfDifferentSpecs) {
  ScratchDir dir("mismatch");
  std::string other = tiny_spec();
  other.replace(other.find("particles = [3, 5, 8]"), 21, "particles = [3]");
  write_text(dir / "other.toml", other);
  ASSERT_EQ(run_to_end({binary_, "sweep", dir / "other.toml", "--out", dir / "other", "--shard", "1/3"}, dir / "o.log"), 0);
  EXPECT_EQ(run_to_end({binary_, "merge", *scratch_ / "reference", dir / "other", "--out", dir / "merged"}, dir / "m.log"), 2);
  EXPECT_NE(read_text(dir / "m.log").find("another spec"), std::string::npos) << read_text(dir / "m.log");
  // Resuming into a directory of another sweep is refused the same way.
  EXPECT_EQ(run_to_end({binary_, "sweep", dir / "other.toml", "--out", *scratch_ / "reference"}, dir / "r.log"), 2);
}

// A row whose key is not in the spec's grid (an edited file, rows of another sweep pasted in) was counted as a
// grid run: "9 of 8 grid runs present". Merge names its file, line and field instead.
TEST_F(SweepEndToEnd, MergeRefusesARowOutsideTheGrid) {
  ScratchDir dir("outside");
  std::filesystem::copy(*scratch_ / "reference", dir / "edited", std::filesystem::copy_options::recursive);
  const std::string jsonl = (dir / "edited") + "/results.jsonl";
  std::string text = read_text(jsonl);
  const std::string first_row = text.substr(0, text.find('\n') + 1);
  std::string stray = first_row;
  stray.replace(stray.find("\"key\":\"") + 7, 0, "elsewhere-");
  write_text(jsonl, text + stray);
  const int lines = static_cast<int>(std::count(text.begin(), text.end(), '\n')) + 1;
  EXPECT_EQ(run_to_end({binary_, "merge", *scratch_ / "reference", dir / "edited", "--out", dir / "merged"}, dir / "m.log"), 2);
  const std::string log = read_text(dir / "m.log");
  EXPECT_NE(log.find(fmt::format("results.jsonl:{}: field 'key'", lines)), std::string::npos) << log;
  EXPECT_NE(log.find("not in the sweep's grid"), std::string::npos) << log;
}

// Runs are deterministic, so two finished rows of one run key that disagree on a result are a conflict (shards
// of different builds, or an edited file): merge names the row and the field instead of keeping the first.
TEST_F(SweepEndToEnd, MergeRefusesTwoFinishedRowsOfOneRunThatDisagree) {
  ScratchDir dir("conflict");
  std::filesystem::copy(*scratch_ / "reference", dir / "edited", std::filesystem::copy_options::recursive);
  const std::string jsonl = (dir / "edited") + "/results.jsonl";
  std::string text = read_text(jsonl);
  const std::size_t field = text.find("\"ate_rmse_m\":");
  ASSERT_NE(field, std::string::npos);
  ASSERT_LT(field, text.find('\n')) << "the first row must hold the field";
  const std::size_t value = field + std::string("\"ate_rmse_m\":").size();
  text.replace(value, text.find(',', value) - value, "99.5");
  write_text(jsonl, text);
  EXPECT_EQ(run_to_end({binary_, "merge", *scratch_ / "reference", dir / "edited", "--out", dir / "merged"}, dir / "m.log"), 2);
  const std::string log = read_text(dir / "m.log");
  EXPECT_NE(log.find("results.jsonl:1: field 'ate_rmse_m'"), std::string::npos) << log;
  EXPECT_NE(log.find("99.5"), std::string::npos) << log;
}

// Two processes never write one --out: while one holds the directory (here this test, as the binary sees
// it), a sweep into it exits 2 before writing anything, whatever its spec.
TEST_F(SweepEndToEnd, ASecondProcessIntoTheSameOutIsRefused) {
  ScratchDir dir("locked");
  std::filesystem::create_directories(dir / "out");
  {
    const DirectoryLock held(dir / "out");
    EXPECT_EQ(run_to_end({binary_, "sweep", spec(), "--out", dir / "out"}, dir / "locked.log"), 2);
    EXPECT_NE(read_text(dir / "locked.log").find("another process"), std::string::npos) << read_text(dir / "locked.log");
    EXPECT_FALSE(std::filesystem::exists(dir / "out/sweep.json"));
  }
  // Released (as when the other process ends, however it ends): the same command runs.
  EXPECT_EQ(run_to_end({binary_, "sweep", spec(), "--out", dir / "out", "--jobs", "2"}, dir / "free.log"), 0)
      << read_text(dir / "free.log");
}

// --retry-failed appended each retried run's ok row after its failed one, and results.csv kept both until the
// next start: whoever read it directly counted every retried run twice (hostile B10).
TEST_F(SweepEndToEnd, RetriedRunsReplaceTheirFailedRows) {
  ScratchDir dir("retry");
  write_text(dir / "w.scn", "not a scenario\n");  // every run fails on it
  write_text(dir / "d.toml", "[scenarios]\ndatasets = [\"w.scn\"]\n[grid]\nfilter = \"fastslam1\"\nmap = \"naive\"\n"
                             "assoc = \"known\"\nparticles = 3\nseed = { from = 1, to = 2 }\nthreads = 1\n");
  const std::vector<std::string> sweep{binary_, "sweep", dir / "d.toml", "--out", dir / "out"};
  run_to_end(sweep, dir / "first.log");
  ASSERT_EQ(rows_of(dir / "out").size(), 2u) << read_text(dir / "first.log");
  ASSERT_EQ(run_to_end({binary_, "simulate", "--landmarks", "20", "--steps", "10", "--out", dir / "w.scn"}, dir / "s.log"), 0);
  std::vector<std::string> retry = sweep;
  retry.push_back("--retry-failed");
  ASSERT_EQ(run_to_end(retry, dir / "retry.log"), 0) << read_text(dir / "retry.log");
  const auto rows = rows_of(dir / "out");  // also checks that results.csv holds as many rows as results.jsonl
  ASSERT_EQ(rows.size(), 2u) << read_text(dir / "out/results.csv");
  for (const auto& r : rows) EXPECT_NE(r.find("status=\"ok\""), std::string::npos) << r;
}

// Merge re-read each shard's copy of the spec, whose relative dataset path resolved from the shard's directory:
// the documented Slurm layout (--out .../shard-N) could not merge a dataset sweep, nor could any sweep whose
// dataset was moved since (hostile C1). Merge needs the grid's keys, not the datasets.
TEST_F(SweepEndToEnd, DatasetShardsMergeWhereverTheirDatasetIs) {
  ScratchDir dir("dataset_shards");
  std::filesystem::create_directories(dir / "specs");
  std::filesystem::create_directories(dir / "data");
  ASSERT_EQ(run_to_end({binary_, "simulate", "--landmarks", "20", "--steps", "10", "--out", dir / "data/w.scn"}, dir / "s.log"), 0);
  write_text(dir / "specs/d.toml", "[scenarios]\ndatasets = [\"../data/w.scn\"]\n[grid]\nfilter = \"fastslam1\"\n"
                                   "map = \"naive\"\nassoc = \"known\"\nparticles = 3\nseed = { from = 1, to = 2 }\n"
                                   "threads = 1\n");
  for (int i = 0; i < 2; ++i)
    ASSERT_EQ(run_to_end({binary_, "sweep", dir / "specs/d.toml", "--out", dir / fmt::format("shards/sh{}", i), "--shard",
                          fmt::format("{}/2", i)}, dir / "shard.log"), 0)
        << read_text(dir / "shard.log");
  std::filesystem::remove(dir / "data/w.scn");
  ASSERT_EQ(run_to_end({binary_, "merge", dir / "shards/sh0", dir / "shards/sh1", "--out", dir / "merged"}, dir / "m.log"), 0)
      << read_text(dir / "m.log");
  EXPECT_EQ(rows_of(dir / "merged").size(), 2u);
}

// The run keys name a dataset by its path: a dataset regenerated between two shards (or before a resume) mixed
// rows of two versions under one key, and merge counted "4 of 4 grid runs present" (hostile B6). sweep.json
// records each dataset's fingerprint; the resume and the merge compare them.
TEST_F(SweepEndToEnd, ADatasetChangedBetweenShardsIsRefused) {
  ScratchDir dir("dataset_changed");
  const auto simulate = [&](const char* seed) {
    return run_to_end({binary_, "simulate", "--landmarks", "20", "--steps", "10", "--seed", seed, "--out", dir / "w.scn"},
                      dir / "s.log");
  };
  ASSERT_EQ(simulate("1"), 0);
  write_text(dir / "d.toml", "[scenarios]\ndatasets = [\"w.scn\"]\n[grid]\nfilter = \"fastslam1\"\nmap = \"naive\"\n"
                             "assoc = \"known\"\nparticles = 3\nseed = { from = 1, to = 2 }\nthreads = 1\n");
  const auto shard = [&](int i) {
    return run_to_end({binary_, "sweep", dir / "d.toml", "--out", dir / fmt::format("sh{}", i), "--shard",
                       fmt::format("{}/2", i)}, dir / fmt::format("sh{}.log", i));
  };
  ASSERT_EQ(shard(0), 0) << read_text(dir / "sh0.log");
  ASSERT_EQ(simulate("9"), 0);  // the dataset is regenerated
  ASSERT_EQ(shard(1), 0) << read_text(dir / "sh1.log");
  EXPECT_EQ(run_to_end({binary_, "merge", dir / "sh0", dir / "sh1", "--out", dir / "merged"}, dir / "m.log"), 2);
  EXPECT_NE(read_text(dir / "m.log").find("field 'datasets': dataset 'w.scn' had other content"), std::string::npos)
      << read_text(dir / "m.log");
  // Resuming the first shard with the new file is refused the same way; with the old one back it is not.
  EXPECT_EQ(shard(0), 2);
  EXPECT_NE(read_text(dir / "sh0.log").find("dataset 'w.scn' has changed since this directory's runs"), std::string::npos)
      << read_text(dir / "sh0.log");
  ASSERT_EQ(simulate("1"), 0);
  EXPECT_EQ(shard(0), 0) << read_text(dir / "sh0.log");
}

// A simulation the sweep's time limit stopped recorded its runs as "failed ... killed by signal 9" rather than
// as a timeout (hostile C6). A million-step world cannot be simulated in the 10 ms the spec allows.
TEST_F(SweepEndToEnd, ASimulationPastTheTimeLimitIsATimeout) {
  ScratchDir dir("simulate_timeout");
  write_text(dir / "t.toml", "[sweep]\ntimeout_s = 0.01\n[scenarios]\nworld = \"uniform\"\nlandmarks = 1000\n"
                             "steps = 1000000\nclutter = 0.0\n[grid]\nfilter = \"fastslam1\"\nmap = \"naive\"\n"
                             "assoc = \"known\"\nparticles = 3\nseed = 1\nthreads = 1\n");
  run_to_end({binary_, "sweep", dir / "t.toml", "--out", dir / "out"}, dir / "t.log");
  const auto rows = read_result_rows(dir / "out/results.jsonl");
  ASSERT_EQ(rows.size(), 1u) << read_text(dir / "t.log");
  EXPECT_EQ(rows[0]["status"], "timeout") << rows[0].dump();
  EXPECT_NE(rows[0]["error"].get<std::string>().find("arbor simulate stopped after the 0.01 s limit"), std::string::npos)
      << rows[0].dump();
}

TEST_F(SweepEndToEnd, MalformedSpecFailsBeforeAnyRunNamingTheLine) {
  ScratchDir dir("malformed");
  std::string bad = tiny_spec();
  bad.replace(bad.find("map = \"naive\""), 13, "map = \"splay\"");
  write_text(dir / "bad.toml", bad);
  EXPECT_EQ(run_to_end({binary_, "sweep", dir / "bad.toml", "--out", dir / "out"}, dir / "bad.log"), 2);
  const std::string log = read_text(dir / "bad.log");
  EXPECT_NE(log.find("bad.toml:13: field 'grid.map'"), std::string::npos) << log;
  EXPECT_FALSE(std::filesystem::exists(dir / "out")) << "something was written before validation finished";
}

}  // namespace
}  // namespace arbor
