#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/TextColumns.h>

#include <cmath>
#include <fstream>
#include <iomanip>
#include <set>
#include <sstream>
#include <stdexcept>

namespace mrpt_vslam::core {
namespace {

/// Whether a comment line names a `yaw` column (view maps).
bool commentNamesYaw(const std::string& line)
{
    std::istringstream ss(line.substr(line.find('#') + 1));
    std::string token;
    while (ss >> token)
        if (token == "yaw") return true;
    return false;
}

TLandmark landmarkFromValues(const std::vector<double>& v, int line_order, bool is_view,
                             const std::string& where)
{
    TLandmark lm;
    const size_t first = v.size() == 3 ? 0 : 1;
    if (first == 1) {
        if (v[0] != std::floor(v[0]) || std::abs(v[0]) > 2e9)
            throw std::runtime_error(where + "id must be an integer");
        lm.id = static_cast<int>(v[0]);
    } else {
        lm.id = line_order;
    }
    if (is_view) {
        lm.position = {v[first], v[first + 1], 0};
        lm.yaw = v[first + 2];
    } else {
        lm.position = {v[first], v[first + 1], v[first + 2]};
    }
    if (v.size() == 10) {
        // Upper triangle: c00 c01 c02 c11 c12 c22.
        const double* c = &v[4];
        lm.cov << c[0], c[1], c[2], c[1], c[3], c[4], c[2], c[4], c[5];
        if (c[0] < 0 || c[3] < 0 || c[5] < 0) throw std::runtime_error(where + "negative variance");
        lm.has_cov = true;
    }
    return lm;
}

}  // namespace

LandmarkFile LandmarkFile::loadTrueLandmarks(const std::string& file)
{
    auto truth = load(file);
    if (truth.empty()) throw std::runtime_error(file + ": no landmarks");
    return truth;
}

LandmarkFile LandmarkFile::load(const std::string& file)
{
    std::ifstream in(file);
    if (!in) throw std::runtime_error(file + ": cannot open landmark file");
    LandmarkFile out;
    std::set<int> ids;
    size_t columns = 0;
    std::string line;
    for (int lineNum = 1; std::getline(in, line); lineNum++) {
        const auto first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos) continue;
        if (line[first] == '#') {
            if (out.landmarks.empty() && commentNamesYaw(line)) out.is_view_map = true;
            continue;
        }
        const auto where = file + ":" + std::to_string(lineNum) + ": ";
        const auto values = parseNumbers(line, where);
        if (values.size() != 3 && values.size() != 4 && values.size() != 10)
            throw std::runtime_error(where +
                                     "expected 3 ('x y z'), 4 ('id x y z') or 10 "
                                     "('id x y z' + covariance) columns, got " +
                                     std::to_string(values.size()));
        if (columns == 0) columns = values.size();
        if (values.size() != columns)
            throw std::runtime_error(where + "expected " + std::to_string(columns) +
                                     " columns like the lines before, got " +
                                     std::to_string(values.size()));
        if (out.is_view_map && columns == 3)
            throw std::runtime_error(where + "a view map needs ids ('id x y yaw')");
        auto lm = landmarkFromValues(values, static_cast<int>(out.landmarks.size()),
                                     out.is_view_map, where);
        if (!ids.insert(lm.id).second)
            throw std::runtime_error(where + "repeated id " + std::to_string(lm.id));
        out.landmarks.push_back(lm);
    }
    return out;
}

void LandmarkFile::save(const std::string& file, const std::string& header_comment) const
{
    bool allCov = !landmarks.empty();
    for (const auto& lm : landmarks) allCov = allCov && lm.has_cov;
    const char* third = is_view_map ? "yaw" : "z";
    AtomicFile out(file);
    auto& os = out.stream();
    if (!header_comment.empty()) os << "# " << header_comment << "\n";
    os << "# id x y " << third;
    if (allCov)
        os << (is_view_map ? " cxx cxy cxyaw cyy cyyaw cyawyaw" : " cxx cxy cxz cyy cyz czz");
    os << "\n" << std::setprecision(9);
    for (const auto& lm : landmarks) {
        os << lm.id << ' ' << lm.position.x << ' ' << lm.position.y << ' '
           << (is_view_map ? lm.yaw : lm.position.z);
        if (allCov) {
            const auto& c = lm.cov;
            os << ' ' << c(0, 0) << ' ' << c(0, 1) << ' ' << c(0, 2) << ' ' << c(1, 1) << ' '
               << c(1, 2) << ' ' << c(2, 2);
        }
        os << '\n';
    }
    out.commit();
}

}  // namespace mrpt_vslam::core
