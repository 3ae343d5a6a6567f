// SPDX-License-Identifier: MIT
// Replay driver for fuzz targets when libFuzzer is not linked (gcc builds, CI): runs
// LLVMFuzzerTestOneInput over every file of the given corpus folders/files, then over a
// fixed-seed stream of mutations of them (bit flips, truncation, splicing, random bytes), so
// each parser's fuzz target runs in every CI build. A crash or sanitizer report fails the test.
//
//   fuzz_x [--iterations=N] [--seed=S] CORPUS...
//
// HIL_FUZZ_SAVE=FILE writes every input to FILE before running it, so after a crash FILE holds
// the input that crashed (add it to the corpus as a regression once fixed).

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <string_view>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

using Bytes = std::vector<std::uint8_t>;

void load(const std::filesystem::path& p, std::vector<Bytes>& out) {
  if (std::filesystem::is_directory(p)) {
    std::vector<std::filesystem::path> files;
    for (const auto& e : std::filesystem::recursive_directory_iterator(p))
      if (e.is_regular_file()) files.push_back(e.path());
    std::sort(files.begin(), files.end());  // deterministic order
    for (const auto& f : files) load(f, out);
    return;
  }
  std::ifstream in(p, std::ios::binary);
  if (!in) return;
  out.emplace_back(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

Bytes mutate(const std::vector<Bytes>& corpus, std::mt19937_64& rng) {
  std::uniform_int_distribution<int> op(0, 5);
  Bytes b = corpus.empty() ? Bytes{} : corpus[rng() % corpus.size()];
  const int rounds = 1 + static_cast<int>(rng() % 4);
  for (int r = 0; r < rounds; ++r) {
    switch (op(rng)) {
      case 0:  // flip a bit
        if (!b.empty()) b[rng() % b.size()] ^= static_cast<std::uint8_t>(1u << (rng() % 8));
        break;
      case 1:  // replace a byte
        if (!b.empty()) b[rng() % b.size()] = static_cast<std::uint8_t>(rng());
        break;
      case 2:  // truncate
        if (!b.empty()) b.resize(rng() % b.size());
        break;
      case 3:  // insert random bytes
        for (int i = 0, n = static_cast<int>(rng() % 8); i < n; ++i)
          b.insert(b.begin() + static_cast<std::ptrdiff_t>(b.empty() ? 0 : rng() % (b.size() + 1)),
                   static_cast<std::uint8_t>(rng()));
        break;
      case 4:  // splice with another corpus entry
        if (!corpus.empty()) {
          const Bytes& o = corpus[rng() % corpus.size()];
          if (!o.empty()) {
            std::size_t from = rng() % o.size();
            b.insert(b.end(), o.begin() + static_cast<std::ptrdiff_t>(from), o.end());
          }
        }
        break;
      default:  // fully random
        b.resize(rng() % 64);
        for (auto& c : b) c = static_cast<std::uint8_t>(rng());
    }
  }
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  long iterations = 10000;
  std::uint64_t seed = 0x48494c42;  // "HILB"
  std::vector<Bytes> corpus;
  for (int i = 1; i < argc; ++i) {
    std::string_view a = argv[i];
    if (a.starts_with("--iterations="))
      iterations = std::strtol(argv[i] + 13, nullptr, 10);
    else if (a.starts_with("--seed="))
      seed = std::strtoull(argv[i] + 7, nullptr, 10);
    else
      load(argv[i], corpus);
  }
  const char* save = std::getenv("HIL_FUZZ_SAVE");
  const auto run = [save](const Bytes& b) {
    if (save != nullptr) {
      std::ofstream out(save, std::ios::binary | std::ios::trunc);
      out.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
    }
    LLVMFuzzerTestOneInput(b.data(), b.size());
  };
  for (const auto& b : corpus) run(b);
  std::mt19937_64 rng(seed);
  for (long i = 0; i < iterations; ++i) run(mutate(corpus, rng));
  std::printf("fuzz replay: %zu corpus inputs, %ld mutated inputs, no crash\n", corpus.size(), iterations);
  return 0;
}
