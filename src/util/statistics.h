// Counters and phase timings of one run: printed as a summary and written by --stats.
#pragma once

#include <chrono>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace candela {

struct RayCounts {
  uint64_t primary = 0;
  uint64_t shadow = 0;
  uint64_t reflected = 0;
  uint64_t refracted = 0;

  RayCounts& operator+=(const RayCounts& other) {
    primary += other.primary;
    shadow += other.shadow;
    reflected += other.reflected;
    refracted += other.refracted;
    return *this;
  }
  uint64_t total() const { return primary + shadow + reflected + refracted; }
};

class Stopwatch {
 public:
  Stopwatch() : start_(std::chrono::steady_clock::now()) {}
  double seconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_;
};

struct RunStatistics {
  std::vector<std::pair<std::string, double>> phases;  // name, seconds
  RayCounts rays;
  uint64_t pixels = 0;
  int threads = 0;
  // Region-sized, row by row; empty for methods that do not report them. primary_per_pixel:
  // the primary rays traced for each pixel (a sample shared by several pixels counts once, for
  // the pixel whose square holds it); samples_per_pixel: the samples each pixel's value used.
  std::vector<uint32_t> primary_per_pixel;
  std::vector<uint32_t> samples_per_pixel;
  nlohmann::json extra = nlohmann::json::object();  // scene and method facts

  void add_phase(std::string name, double seconds) { phases.emplace_back(std::move(name), seconds); }
  // Takes what another run measured (a method's render) after what this one holds: its phases
  // follow these, counts add, per-pixel vectors and facts replace (threads stay).
  void absorb(RunStatistics&& other);
  nlohmann::json to_json() const;
  std::string summary() const;  // one screen of text
};

// Peak resident memory of this process in bytes (0 when unknown).
uint64_t peak_memory_bytes();

}  // namespace candela
