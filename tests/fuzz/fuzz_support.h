// Shared by the libFuzzer targets: every reader in Arbor takes a path, so an input is written to a file in
// a per-process scratch directory first. An InputError is the reader doing its job; anything else that
// escapes (another exception, an abort, a sanitizer report, a hang) is a finding.
#ifndef ARBOR_TESTS_FUZZ_FUZZ_SUPPORT_H_
#define ARBOR_TESTS_FUZZ_FUZZ_SUPPORT_H_

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

#include "core/io/input_error.h"
#include "core/io/scenario_format.h"
#include "core/types/scenario.h"

namespace arbor::fuzz {

// A directory of this process's own under the system temp dir, created on first use.
inline const std::filesystem::path& scratch_dir() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("arbor_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

inline void write_bytes(const std::filesystem::path& path, std::string_view bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
}

inline std::string read_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The input as one file, named name in the scratch directory; returns its path.
inline std::string input_file(const std::uint8_t* data, std::size_t size, const std::string& name) {
  const auto path = scratch_dir() / name;
  write_bytes(path, std::string_view(reinterpret_cast<const char*>(data), size));
  return path.string();
}

// A dataset directory (a copy of the one shipped in tests/data) in which one file at a time is the fuzz
// input. The first byte of the input picks the file ('0' the first, modulo the count), the rest is its
// content; after a load the file gets its original bytes back, so every input mutates exactly one file of a
// valid dataset.
class DatasetCopy {
 public:
  DatasetCopy(const std::string& source_dir, std::vector<std::string> files) : files_(std::move(files)) {
    dir_ = scratch_dir() / std::filesystem::path(source_dir).filename();
    std::filesystem::remove_all(dir_);
    std::filesystem::copy(source_dir, dir_, std::filesystem::copy_options::recursive);
    for (const auto& f : files_) originals_.push_back(read_bytes(dir_ / f));
  }
  const std::string dir() const { return dir_.string(); }

  // Runs load(dir) with the input's file replaced, then restores it.
  template <class Load>
  void with_input(const std::uint8_t* data, std::size_t size, Load&& load) {
    if (size == 0) return;
    const std::size_t which = static_cast<unsigned char>(data[0] - '0') % files_.size();
    write_bytes(dir_ / files_[which], std::string_view(reinterpret_cast<const char*>(data) + 1, size - 1));
    struct Restore {
      DatasetCopy* copy;
      std::size_t which;
      ~Restore() { write_bytes(copy->dir_ / copy->files_[which], copy->originals_[which]); }
    } restore{this, which};
    load(dir());
  }

 private:
  std::filesystem::path dir_;
  std::vector<std::string> files_;
  std::vector<std::string> originals_;
};

// Runs f: true when the input was accepted, false when it was refused with an InputError (the reader doing its
// job). Anything else escapes to libFuzzer, as a finding.
template <class F>
bool accepted(F&& f) {
  try {
    f();
    return true;
  } catch (const InputError&) {
    return false;
  }
}

// A dataset converter's target body: convert(dir) on copy with the input in place of one of its files, then
// the scenario writer on what it returns.
template <class Convert>
void convert_and_write(DatasetCopy& copy, const std::uint8_t* data, std::size_t size, Convert&& convert) {
  copy.with_input(data, size, [&](const std::string& dir) {
    accepted([&] { write_scenario(convert(dir), (scratch_dir() / "out.scn").string()); });
  });
}

}  // namespace arbor::fuzz

#endif  // ARBOR_TESTS_FUZZ_FUZZ_SUPPORT_H_
