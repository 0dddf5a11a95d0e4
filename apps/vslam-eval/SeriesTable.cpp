#include "SeriesTable.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace mrpt_vslam::eval {

SeriesTable SeriesTable::load(const std::string& file)
{
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot open file for reading");
    SeriesTable t;
    std::string text;
    for (size_t line = 1; std::getline(in, text); line++) {
        const auto fail = [&](const std::string& what) {
            throw std::runtime_error(file + ":" + std::to_string(line) + ": " + what);
        };
        std::istringstream ss(text);
        std::string name;
        if (!(ss >> name) || name[0] == '#') continue;
        std::vector<double> v;
        std::string word;
        while (ss >> word) {
            size_t used = 0;
            double d = 0;
            try {
                d = std::stod(word, &used);
            } catch (const std::exception&) {
                used = 0;
            }
            if (used != word.size() || !std::isfinite(d))
                fail("'" + word + "' is not a finite number");
            v.push_back(d);
        }
        if (v.size() != 2 && v.size() != 4) fail("expected 'SERIES X Y' or 'SERIES X Y LOW HIGH'");
        TSeries* s = nullptr;
        for (auto& e : t.series)
            if (e.name == name) s = &e;
        if (!s) s = &t.series.emplace_back(TSeries{name, {}, {}, {}, {}});
        if (!s->x.empty() && (v.size() == 4) != !s->low.empty())
            fail("series '" + name + "' mixes points with and without a LOW HIGH band");
        s->x.push_back(v[0]);
        s->y.push_back(v[1]);
        if (v.size() == 4) s->low.push_back(v[2]), s->high.push_back(v[3]);
    }
    if (t.series.empty()) throw std::runtime_error(file + ": no points");
    return t;
}

}  // namespace mrpt_vslam::eval
