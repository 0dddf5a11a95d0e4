#include <mrpt/io/CFileGZOutputStream.h>
#include <mrpt/opengl/CText.h>
#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/RunOutputs.h>

#include <filesystem>
#include <stdexcept>
#include <vector>

namespace mrpt_vslam::core {

namespace {
template <class T>
void saveGz(const T& obj, const std::string& file)
{
    const std::string tmp = file + ".tmp";
    try {
        {
            mrpt::io::CFileGZOutputStream out;
            if (!out.open(tmp)) throw std::runtime_error(file + ": cannot create file for writing");
            mrpt::serialization::archiveFrom(out) << obj;
        }
        AtomicFile::commitRename(tmp, file);
    } catch (...) {  // no part-written file left behind
        std::error_code ec;
        std::filesystem::remove(tmp, ec);
        throw;
    }
}
}  // namespace

void saveObjectGz(const mrpt::serialization::CSerializable& obj, const std::string& file)
{
    saveGz(obj, file);
}

void saveMapFiles(const mrpt::maps::CMetricMap& map, const std::string& out_dir,
                  const std::string& prefix)
{
    namespace fs = std::filesystem;
    const std::string tmp = prefix + ".tmp";
    std::vector<fs::path> written;  // PREFIX.tmp*, each renamed to PREFIX*
    try {
        map.saveMetricMapRepresentationToFile((fs::path(out_dir) / tmp).string());
        for (const auto& entry : fs::directory_iterator(out_dir))
            if (entry.path().filename().string().rfind(tmp, 0) == 0)
                written.push_back(entry.path());
        for (const auto& file : written)
            AtomicFile::commitRename(
                file.string(),
                (fs::path(out_dir) / (prefix + file.filename().string().substr(tmp.size())))
                    .string());
    } catch (...) {  // no part-written file left behind
        std::error_code ec;
        std::vector<fs::path> left;
        for (const auto& entry : fs::directory_iterator(out_dir, ec))
            if (entry.path().filename().string().rfind(tmp, 0) == 0) left.push_back(entry.path());
        for (const auto& file : left) fs::remove(file, ec);
        throw;
    }
}

void saveFinalMap(const mrpt::maps::CMetricMap& map, const std::string& out_dir)
{
    saveMapFiles(map, out_dir, "map");
    saveObjectGz(map, (std::filesystem::path(out_dir) / "final_map.gz").string());
}

void saveScene(const mrpt::opengl::COpenGLScene& scene, const std::string& file)
{
    saveGz(scene, file);
}

mrpt::opengl::CSetOfObjects::Ptr trajectoryAsLines(const TumTrajectory& path,
                                                   const mrpt::img::TColorf& color,
                                                   const std::string& label, float width)
{
    auto group = mrpt::opengl::CSetOfObjects::Create();
    group->setName(label);
    if (path.size() < 2) return group;
    auto lines = mrpt::opengl::CSetOfLines::Create();
    lines->setColor(color);
    lines->setLineWidth(width);
    for (size_t i = 1; i < path.size(); i++) {
        const auto& a = path.poses[i - 1];
        const auto& b = path.poses[i];
        lines->appendLine(a.x, a.y, a.z + 0.01, b.x, b.y, b.z + 0.01);
    }
    group->insert(lines);
    auto text = mrpt::opengl::CText::Create(label);
    text->setColor(color);
    const auto& last = path.poses.back();
    text->setLocation(last.x, last.y, last.z + 0.2);
    group->insert(text);
    return group;
}

mrpt::opengl::CSetOfLines::Ptr pointsAsCrosses(const std::vector<mrpt::math::TPoint3D>& points,
                                               const mrpt::img::TColorf& color, double size)
{
    auto lines = mrpt::opengl::CSetOfLines::Create();
    lines->setColor(color);
    lines->setLineWidth(2);
    const double h = size / 2;
    for (const auto& p : points) {
        lines->appendLine(p.x - h, p.y, p.z, p.x + h, p.y, p.z);
        lines->appendLine(p.x, p.y - h, p.z, p.x, p.y + h, p.z);
        lines->appendLine(p.x, p.y, p.z - h, p.x, p.y, p.z + h);
    }
    return lines;
}

}  // namespace mrpt_vslam::core
