// The sweep executor: scenario generation, a pool of child runs, result rows, progress; see sweep_runner.h.
#include "experiments/sweep/sweep_runner.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <ctime>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <fmt/core.h>

#include "core/io/atomic_file.h"
#include "core/io/build_info.h"
#include "core/io/directory_lock.h"
#include "core/io/input_error.h"
#include "experiments/run/progress.h"
#include "experiments/sweep/child_process.h"
#include "experiments/sweep/results_log.h"
#include "experiments/sweep/sweep_manifest.h"
#include "variants/filter_list.h"

namespace arbor {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void on_stop_signal(int sig) { g_stop_signal = sig; }

std::string duration_text(double seconds) {
  if (!std::isfinite(seconds) || seconds < 0) return "--";
  const auto s = static_cast<long long>(std::llround(seconds));
  return fmt::format("{}:{:02}:{:02}", s / 3600, (s / 60) % 60, s % 60);
}

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  std::tm tm{};
  ::gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// One child to run and what to do when it ends.
struct Job {
  std::string label;
  std::vector<std::string> argv;
  std::string log_path;
  std::function<void(const ChildExit&, double wall_s)> on_exit;
};

// Runs jobs up to `parallel` at a time, calling progress() after each completion and every heartbeat_s.
// Returns false when a SIGINT/SIGTERM stopped it (running children are killed; their rows are not written).
bool run_jobs(std::deque<Job> jobs, int parallel, double timeout_s, double heartbeat_s,
              const std::function<void(int running)>& progress) {
  struct Running {
    Job job;
    Clock::time_point start;
    bool timed_out = false;
  };
  std::map<pid_t, Running> running;
  auto last_progress = Clock::now();
  while (!jobs.empty() || !running.empty()) {
    if (g_stop_signal != 0) {
      for (auto& [pid, r] : running) ::kill(pid, SIGTERM);
      for (auto& [pid, r] : running) wait_child(pid);
      return false;
    }
    while (!jobs.empty() && static_cast<int>(running.size()) < parallel) {
      Job job = std::move(jobs.front());
      jobs.pop_front();
      const pid_t pid = start_child(job.argv, job.log_path);
      running.emplace(pid, Running{std::move(job), Clock::now()});
    }
    bool reaped = false;
    while (auto done = poll_children()) {
      const auto it = running.find(done->first);
      if (it == running.end()) continue;
      const double wall = std::chrono::duration<double>(Clock::now() - it->second.start).count();
      ChildExit exit = done->second;
      exit.timed_out = it->second.timed_out;
      Job job = std::move(it->second.job);
      running.erase(it);
      job.on_exit(exit, wall);
      reaped = true;
    }
    if (timeout_s > 0) {
      for (auto& [pid, r] : running)
        if (!r.timed_out && std::chrono::duration<double>(Clock::now() - r.start).count() > timeout_s) {
          r.timed_out = true;
          ::kill(pid, SIGKILL);
        }
    }
    if (reaped || Clock::now() - last_progress > std::chrono::duration<double>(heartbeat_s)) {
      progress(static_cast<int>(running.size()));
      last_progress = Clock::now();
    }
    if (!reaped) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return true;
}

using Json = nlohmann::ordered_json;

std::optional<Json> read_result_json(const std::string& path, std::string* error) {
  std::ifstream in(path);
  if (!in) {
    *error = "run exited 0 but wrote no result.json";
    return std::nullopt;
  }
  try {
    Json doc = Json::parse(in);
    if (doc.is_object()) return doc;
    *error = path + ": result.json is not a JSON object";
  } catch (const nlohmann::json::parse_error& e) {
    *error = fmt::format("{}: malformed JSON: {}", path, e.what());
  }
  return std::nullopt;
}

// A scalar of result.json's "config" object, or nullptr.
const Json* config_field(const Json* result, const char* name) {
  if (!result || !result->contains("config") || !(*result)["config"].is_object()) return nullptr;
  const Json& config = (*result)["config"];
  const auto it = config.find(name);
  return it != config.end() && it->is_primitive() && !it->is_null() ? &*it : nullptr;
}

// Assembles a row with exactly `columns`, in order.
ResultRow make_row(const RunParams& run, const std::vector<std::string>& columns, const std::vector<std::string>& metrics,
                   const std::string& status, const std::string& error, const Json* result, const ChildExit* exit,
                   double wall_s) {
  std::map<std::string, Json> cells;
  for (auto& [name, value] : param_cells(run)) cells[name] = value;
  cells["status"] = status;
  cells["error"] = error.empty() ? Json() : Json(error);
  for (const auto& m : metrics) {
    const auto it = result ? result->find(m) : Json::const_iterator();
    cells[m] = result && it != result->end() && it->is_primitive() ? *it : Json();
  }
  // Provenance from the run itself (its result.json), else from this process: the same binary.
  const auto provenance = [&](const char* name, const std::string& mine) {
    const Json* v = config_field(result, name);
    cells[name] = v ? *v : Json(mine);
  };
  provenance("commit", git_commit());
  provenance("host", host_name());
  provenance("compiler", compiler());
  provenance("build", build_type());
  cells["process_wall_s"] = wall_s >= 0 ? Json(std::round(wall_s * 1e6) / 1e6) : Json();
  cells["exit_code"] = exit && exit->signal == 0 && exit->exit_code >= 0 ? Json(exit->exit_code) : Json();
  cells["finished_at"] = utc_now();
  ResultRow row = ResultRow::object();
  for (const auto& c : columns) row[c] = cells.count(c) ? cells[c] : Json();
  return row;
}

std::vector<std::string> simulate_command(const RunParams& run, const std::string& exe, const std::string& out_file) {
  return {exe, "simulate", "--world", run.world, "--landmarks", fmt::format("{}", run.world_landmarks), "--steps",
          fmt::format("{}", run.world_steps), "--clutter", fmt::format("{}", run.clutter), "--seed",
          fmt::format("{}", run.simulation_seed()), "--out", out_file};
}

std::string shell_quote(const std::vector<std::string>& argv) {
  std::string out;
  for (const auto& a : argv) {
    const bool plain = !a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=:+") == std::string::npos;
    out += (out.empty() ? "" : " ") + (plain ? a : "'" + a + "'");
  }
  return out;
}

}  // namespace

void parse_shard(const std::string& text, int* index, int* count) {
  const auto slash = text.find('/');
  try {
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    std::size_t used_i = 0, used_n = 0;
    *index = std::stoi(text.substr(0, slash), &used_i);
    *count = std::stoi(text.substr(slash + 1), &used_n);
    if (used_i != slash || used_n != text.size() - slash - 1) throw std::invalid_argument("junk");
  } catch (const std::exception&) {
    throw InputError("--shard", 0, "", fmt::format("expected I/N (e.g. 0/4), got '{}'", text));
  }
  if (*count < 1 || *index < 0 || *index >= *count)
    throw InputError("--shard", 0, "", fmt::format("need 0 <= I < N, got {}/{} (shards are numbered from 0, like Slurm array ids)", *index, *count));
}

std::vector<RunParams> shard_runs(const std::vector<RunParams>& grid, int index, int count) {
  std::vector<RunParams> out;
  for (std::size_t i = 0; i < grid.size(); ++i)
    if (static_cast<int>(i % count) == index) out.push_back(grid[i]);
  return out;
}

std::vector<std::string> run_command(const RunParams& run, const std::string& exe, const std::string& out_dir) {
  const std::string scenario = run.dataset.empty() ? out_dir + "/scenarios/" + run.scenario_name() + ".scn" : run.dataset_path;
  const std::string dir = out_dir + "/runs/" + run.key();
  const FilterEntry& filter = listed_filter(run.filter);
  if (filter.traits.is_batch)
    return {exe, std::string(filter.command), "--scenario", scenario, "--associations", "known", "--out", dir};
  std::vector<std::string> argv{exe, std::string(filter.command), "--scenario", scenario, "--filter", run.filter};
  if (filter.traits.has_map_backends) argv.insert(argv.end(), {"--map", run.map});
  if (filter.traits.chooses_association) argv.insert(argv.end(), {"--assoc", run.assoc});
  if (filter.traits.has_particles) argv.insert(argv.end(), {"--particles", fmt::format("{}", run.particles)});
  argv.insert(argv.end(), {"--seed", fmt::format("{}", run.seed), "--threads", fmt::format("{}", run.threads), "--out", dir});
  for (const auto& [name, value] : run.run_options) argv.push_back(fmt::format("--{}={}", name, value));
  return argv;
}

SweepSummary run_sweep(const SweepSpec& spec, const SweepOptions& options) {
  SweepSummary summary;
  summary.grid_runs = static_cast<int>(spec.runs.size());
  const std::vector<RunParams> mine = shard_runs(spec.runs, options.shard_index, options.shard_count);
  summary.shard_runs = static_cast<int>(mine.size());
  const std::string out = options.out_dir;
  const std::string exe = options.arbor_exe.empty() ? self_executable() : options.arbor_exe;
  const std::vector<std::string> columns = result_columns(spec.metrics, spec.run_option_names);
  const std::string shard = fmt::format("{}/{}", options.shard_index, options.shard_count);

  if (options.dry_run) {
    fmt::print("# sweep '{}' (spec hash {}): {} runs in the grid, {} in shard {}\n", spec.name, spec.hash,
               spec.runs.size(), mine.size(), shard);
    for (const auto& run : mine) fmt::print("{}\t{}\n", run.key(), shell_quote(run_command(run, exe, out)));
    return summary;
  }

  // One process writes a directory at a time, whatever its spec (the lock lives until the sweep returns);
  // then the directory's manifest must match this spec and shard.
  fs::create_directories(out);
  const DirectoryLock lock(out);
  SweepManifest manifest{spec.hash, spec.name, shard, summary.grid_runs, columns};
  for (const RunParams& run : spec.runs)
    if (!run.dataset.empty() && !manifest.datasets.count(run.dataset))
      manifest.datasets[run.dataset] = dataset_fingerprint(run.dataset_path);
  if (const auto existing = read_manifest(out)) {
    if (existing->spec_hash != spec.hash)
      throw InputError(out + "/" + kSweepManifest, 0, "spec_hash",
                       fmt::format("this directory holds another sweep (spec hash {}, this spec {}); use a new --out",
                                   existing->spec_hash, spec.hash));
    if (existing->shard != shard)
      throw InputError(out + "/" + kSweepManifest, 0, "shard",
                       fmt::format("this directory holds shard {}, not {}", existing->shard, shard));
    // Failed rows hold no result to mix (a broken dataset fixed, then --retry-failed): only finished ones count.
    if (const auto dataset = changed_dataset(*existing, manifest); dataset && has_ok_row_of_dataset(out, *dataset))
      throw InputError(out + "/" + kSweepManifest, 0, "datasets",
                       fmt::format("dataset '{}' has changed since this directory's runs (fingerprint {}, now {}): its "
                                   "rows would mix two versions of it; use a new --out",
                                   *dataset, existing->datasets.at(*dataset), manifest.datasets.at(*dataset)));
  }
  write_manifest(out, manifest);
  {
    std::ifstream in(spec.path);
    std::stringstream text;
    text << in.rdbuf();
    write_file_atomically(out + "/spec.toml", text.str());
  }

  // Resume: the rows already recorded (last row per key wins, for --retry-failed) decide what is skipped.
  const std::string jsonl = out + "/" + kResultsJsonl;
  drop_partial_last_line(jsonl);
  const std::vector<ResultRow> kept = last_row_of_each_key(read_result_rows(jsonl));
  std::set<std::string> done;
  for (const ResultRow& row : kept)
    if (!options.retry_failed || row.value("status", std::string()) == "ok") done.insert(row["key"].get<std::string>());
  write_result_files(out, kept, columns);  // the CSV always mirrors the JSONL, even after a kill between the two

  std::vector<RunParams> pending;
  for (const auto& run : mine)
    if (done.count(run.key())) ++summary.already_done;
    else pending.push_back(run);

  const int max_threads = static_cast<int>(std::max_element(spec.runs.begin(), spec.runs.end(), [](auto& a, auto& b) { return a.threads < b.threads; })->threads);
  int jobs = options.jobs > 0 ? options.jobs : spec.jobs.value_or(std::max(1, static_cast<int>(std::thread::hardware_concurrency()) / max_threads));
  jobs = std::max(1, jobs);

  g_stop_signal = 0;
  struct sigaction action{}, old_int{}, old_term{};
  action.sa_handler = on_stop_signal;
  ::sigemptyset(&action.sa_mask);
  ::sigaction(SIGINT, &action, &old_int);
  ::sigaction(SIGTERM, &action, &old_term);
  const auto restore_signals = [&] {
    ::sigaction(SIGINT, &old_int, nullptr);
    ::sigaction(SIGTERM, &old_term, nullptr);
  };

  const auto start = Clock::now();
  fs::create_directories(out + "/logs");
  fs::create_directories(out + "/runs");
  fmt::print(stderr, "[sweep] '{}': {} runs in shard {} of a {}-run grid, {} already recorded, {} to run, {} at a time\n",
             spec.name, mine.size(), shard, spec.runs.size(), summary.already_done, pending.size(), jobs);

  // Phase 1: the simulated scenarios the pending runs need, cached by their parameters in DIR/scenarios/.
  // Scenario name -> the status and error of the runs that need it, where it could not be made.
  std::map<std::string, std::pair<std::string, std::string>> scenario_error;
  {
    std::deque<Job> sims;
    std::set<std::string> queued;
    int finished = 0;  // simulations done, for the progress line
    fs::create_directories(out + "/scenarios");
    for (const auto& run : pending) {
      const std::string name = run.scenario_name();
      if (name.empty() || queued.count(name)) continue;
      queued.insert(name);
      const std::string file = out + "/scenarios/" + name + ".scn";
      if (fs::exists(file)) continue;
      const std::string log = out + "/logs/simulate-" + name + ".log";
      sims.push_back({name, simulate_command(run, exe, file), log, [&, name, file, log](const ChildExit& e, double) {
                        ++finished;
                        // A simulation the time limit stopped is a timeout, as a run would be, not "killed by
                        // signal 9" (hostile C6).
                        if (e.timed_out)
                          scenario_error[name] = {"timeout", fmt::format("arbor simulate stopped after the {} s limit", spec.timeout_s)};
                        else if (!e.ok() || !fs::exists(file))
                          scenario_error[name] = {"failed", fmt::format("arbor simulate failed ({}): {}", e.describe(), last_log_line(log))};
                      }});
    }
    if (!sims.empty()) {
      const int total = static_cast<int>(sims.size());
      ProgressLine line;
      const bool completed = run_jobs(std::move(sims), jobs, spec.timeout_s, 1.0, [&](int) {
        line.show(fmt::format("[sweep] simulating scenarios {}/{}", finished, total),
                  static_cast<double>(finished) / total, finished == total);
      });
      if (!completed) {
        summary.interrupted = true;
        restore_signals();
        return summary;
      }
    }
  }

  // Phase 2: the runs.
  std::deque<Job> runs;
  for (const auto& run : pending) {
    const std::string key = run.key();
    const std::string log = out + "/logs/" + key + ".log";
    const std::string run_dir = out + "/runs/" + key;
    if (auto it = scenario_error.find(run.scenario_name()); !run.scenario_name().empty() && it != scenario_error.end()) {
      append_result_row(out, make_row(run, columns, spec.metrics, it->second.first, it->second.second, nullptr, nullptr, -1), columns);
      ++summary.finished;
      ++summary.failed;
      continue;
    }
    runs.push_back({key, run_command(run, exe, out), log, [&, run, log, run_dir](const ChildExit& e, double wall) {
                      std::string status = "ok", error;
                      std::optional<Json> result;
                      if (e.timed_out) {
                        status = "timeout";
                        error = fmt::format("stopped after the {} s limit", spec.timeout_s);
                      } else if (e.signal != 0) {
                        status = "crashed";
                        const std::string last = last_log_line(log);
                        error = fmt::format("{}; last output: {}", e.describe(), last.empty() ? "(none)" : last);
                      } else if (e.exit_code != 0) {
                        status = "failed";
                        error = fmt::format("{}: {}", e.describe(), last_log_line(log));
                      } else if (!(result = read_result_json(run_dir + "/result.json", &error))) {
                        status = "failed";
                      }
                      append_result_row(out, make_row(run, columns, spec.metrics, status, error, result ? &*result : nullptr, &e, wall), columns);
                      ++summary.finished;
                      if (status != "ok") ++summary.failed;
                    }});
    fs::remove_all(run_dir);  // output of an interrupted earlier attempt
  }
  const int to_run = static_cast<int>(pending.size());
  ProgressLine line;
  const bool completed = run_jobs(std::move(runs), jobs, spec.timeout_s, 1.0, [&](int running) {
    // ETA from this session's pace: runs skipped on resume took no time and must not speed the estimate up.
    const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
    const int remaining = to_run - summary.finished;
    const double eta = summary.finished > 0 ? elapsed / summary.finished * remaining : NAN;
    line.show(fmt::format("[sweep] {}/{} runs done ({} this session, {} running) · {} failed · elapsed {} · ETA {}",
                          summary.already_done + summary.finished, mine.size(), summary.finished, running,
                          summary.failed, duration_text(elapsed), duration_text(eta)),
              to_run > 0 ? static_cast<double>(summary.finished) / to_run : 1.0, remaining == 0);
  });
  summary.interrupted = !completed;
  restore_signals();
  // A retried run appended its new row after its failed one; whoever reads results.csv directly counted both
  // (hostile B10). Keep the newest row of each key, as the next start would.
  if (options.retry_failed) write_result_files(out, last_row_of_each_key(read_result_rows(jsonl)), columns);
  return summary;
}

}  // namespace arbor
