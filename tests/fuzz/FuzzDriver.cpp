// Runs a fuzz target without libFuzzer (builds without MRPT_VSLAM_FUZZ): each seed file as it is,
// then --runs mutations of them (bit flips, overwritten, inserted and removed bytes, truncation,
// a copied chunk), drawn from --seed. A crash or a hang fails the program (and its ctest test);
// exceptions inside the target are its own business.
//   fuzz_TARGET [--runs N] [--seed S] SEED_FILE...
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size);

namespace {
std::vector<uint8_t> readFile(const std::string& file)
{
    std::ifstream in(file, std::ios::binary);
    if (!in) {
        std::fprintf(stderr, "%s: cannot open seed file\n", file.c_str());
        std::exit(2);
    }
    return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<uint8_t> mutate(std::vector<uint8_t> v, std::mt19937& rng)
{
    const auto at = [&](size_t n) { return std::uniform_int_distribution<size_t>(0, n)(rng); };
    const int edits = 1 + static_cast<int>(at(3));
    for (int e = 0; e < edits; e++) {
        if (v.empty()) v.push_back(0);
        const size_t i = at(v.size() - 1);
        switch (at(5)) {
            case 0:
                v[i] ^= static_cast<uint8_t>(1u << at(7));
                break;
            case 1:
                v[i] = static_cast<uint8_t>(at(255));
                break;
            case 2:
                v.insert(v.begin() + static_cast<long>(i), static_cast<uint8_t>(at(255)));
                break;
            case 3:
                v.erase(v.begin() + static_cast<long>(i));
                break;
            case 4:
                v.resize(i);
                break;
            default: {  // a chunk copied elsewhere
                const size_t n = std::min<size_t>(at(64), v.size() - i);
                const std::vector<uint8_t> chunk(v.begin() + static_cast<long>(i),
                                                 v.begin() + static_cast<long>(i + n));
                v.insert(v.begin() + static_cast<long>(at(v.size())), chunk.begin(), chunk.end());
            }
        }
    }
    return v;
}
}  // namespace

int main(int argc, char** argv)
{
    long runs = 100;
    unsigned seed = 1;
    std::vector<std::vector<uint8_t>> seeds;
    for (int i = 1; i < argc; i++) {
        const std::string a = argv[i];
        if (a == "--runs" && i + 1 < argc)
            runs = std::atol(argv[++i]);
        else if (a == "--seed" && i + 1 < argc)
            seed = static_cast<unsigned>(std::atol(argv[++i]));
        else
            seeds.push_back(readFile(a));
    }
    if (seeds.empty()) seeds.emplace_back();
    for (const auto& s : seeds) LLVMFuzzerTestOneInput(s.data(), s.size());
    std::mt19937 rng(seed);
    for (long r = 0; r < runs; r++) {
        const auto input = mutate(seeds[static_cast<size_t>(r) % seeds.size()], rng);
        LLVMFuzzerTestOneInput(input.data(), input.size());
    }
    std::printf("%s: %zu seed inputs and %ld mutations, no crash\n", argv[0], seeds.size(), runs);
    return 0;
}
