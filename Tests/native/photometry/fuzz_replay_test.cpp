// Replays the fuzz seed corpus and deterministic mutations of it through both parsers (with
// the same per-input code as the libFuzzer targets): each input must parse or be rejected
// with an InputError, never crash, hang or throw anything else. Runs in every build.

#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>

#include "fuzz_common.hpp"
#include "photometry_test_util.hpp"

namespace lightsolver {
namespace {

struct Seed {
  std::string name, bytes;
};

std::vector<Seed> seed_corpus() {
  std::vector<Seed> seeds;
  for (const char* dir :
       {"Tests/fuzz/corpus/ies", "Tests/fuzz/corpus/ldt", "Resources/luminaires"}) {
    for (const auto& entry : std::filesystem::directory_iterator(test::repo_path(dir))) {
      const std::string ext = entry.path().extension().string();
      if (ext != ".ies" && ext != ".ldt") continue;
      std::ifstream in(entry.path(), std::ios::binary);
      std::ostringstream buf;
      buf << in.rdbuf();
      seeds.push_back({entry.path().filename().string(), buf.str()});
    }
  }
  std::sort(seeds.begin(), seeds.end(),
            [](const Seed& a, const Seed& b) { return a.name < b.name; });
  return seeds;
}

// Byte-level edits like a fuzzer's, plus tokens that poke at the parsers' checks.
std::string mutate(std::string s, std::mt19937_64& rng) {
  static const char* const kTokens[] = {"-1",
                                        "0",
                                        "nan",
                                        "1e308",
                                        "-1e308",
                                        "999999999",
                                        "\n",
                                        " ",
                                        ",",
                                        "\r",
                                        "TILT=INCLUDE\n",
                                        "-90",
                                        "360",
                                        "[MORE] x\n",
                                        "0.0000001",
                                        "4",
                                        "3",
                                        "+",
                                        "1e-320",
                                        "\x1A",
                                        "\xEF\xBB\xBF"};
  const auto pick = [&](std::size_t n) { return n ? static_cast<std::size_t>(rng() % n) : 0; };
  const int edits = 1 + static_cast<int>(rng() % 3);
  for (int e = 0; e < edits; ++e) {
    const std::size_t at = pick(s.size() + 1);
    switch (rng() % 6) {
      case 0:
        if (!s.empty()) s[pick(s.size())] = static_cast<char>(rng() & 0xFF);
        break;
      case 1:
        s.erase(at, 1 + pick(16));
        break;
      case 2:
        s.insert(at, kTokens[pick(std::size(kTokens))]);
        break;
      case 3:
        s.insert(at, s.substr(pick(s.size()), 1 + pick(64)));
        break;
      case 4:
        s.resize(at);
        break;
      default:  // change a digit: counts and angles drift
        for (std::size_t k = at; k < s.size(); ++k)
          if (s[k] >= '0' && s[k] <= '9') {
            s[k] = static_cast<char>('0' + rng() % 10);
            break;
          }
    }
  }
  return s;
}

bool feed_ies(const std::string& s) {
  return fuzz::one_ies_input(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}
bool feed_ldt(const std::string& s) {
  return fuzz::one_ldt_input(reinterpret_cast<const std::uint8_t*>(s.data()), s.size());
}

TEST(FuzzReplay, SeedCorpusParsesWithItsOwnParserAndNeverCrashesTheOther) {
  const auto seeds = seed_corpus();
  ASSERT_GE(seeds.size(), 20u);
  for (const auto& seed : seeds) {
    const bool is_ies = seed.name.ends_with(".ies");
    bool as_ies = false, as_ldt = false;
    EXPECT_NO_THROW(as_ies = feed_ies(seed.bytes)) << seed.name;
    EXPECT_NO_THROW(as_ldt = feed_ldt(seed.bytes)) << seed.name;
    // Regression seeds are inputs the fuzzer once crashed on: they must now be rejected
    // cleanly. The TILT=<file> seed needs a directory, which in-memory text has not.
    if (seed.name.starts_with("regress_") || seed.name == "lm63_1995_tilt_file.ies") continue;
    EXPECT_TRUE(is_ies ? as_ies : as_ldt) << seed.name << " should parse";
    EXPECT_FALSE(is_ies ? as_ldt : as_ies) << seed.name << " parsed as the other format";
  }
}

TEST(FuzzReplay, DeterministicMutantsParseOrFailCleanly) {
  std::mt19937_64 rng(20250101);
  long parsed = 0, rejected = 0;
  for (const auto& seed : seed_corpus()) {
    const int mutants = seed.bytes.size() > 4000 ? 60 : 300;
    for (int m = 0; m < mutants; ++m) {
      const std::string input = mutate(seed.bytes, rng);
      bool ok = false;
      ASSERT_NO_THROW(ok = seed.name.ends_with(".ies") ? feed_ies(input) : feed_ldt(input))
          << seed.name << " mutant " << m;
      (ok ? parsed : rejected)++;
      ASSERT_NO_THROW(seed.name.ends_with(".ies") ? feed_ldt(input) : feed_ies(input));
    }
  }
  // Not vacuous: mutants exercise both the accepting and the rejecting paths.
  EXPECT_GT(parsed, 500);
  EXPECT_GT(rejected, 500);
}

}  // namespace
}  // namespace lightsolver
