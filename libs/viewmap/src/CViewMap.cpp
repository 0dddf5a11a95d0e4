#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/format.h>
#include <mrpt/math/CMatrixFixed.h>
#include <mrpt/opengl/CEllipsoid2D.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSetOfTriangles.h>
#include <mrpt/opengl/CText.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/viewmap/CViewMap.h>

#include <cmath>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "ArgumentChecks.h"

using mrpt_vslam::viewmap::CViewMap;

MAP_DEFINITION_REGISTER("mrpt_vslam::viewmap::CViewMap,viewMap", mrpt_vslam::viewmap::CViewMap)

IMPLEMENTS_SERIALIZABLE(CViewMap, mrpt::maps::CMetricMap, mrpt_vslam::viewmap)

namespace mrpt_vslam::viewmap {

using core::requireKey;
using detail::requireCovariance;
using detail::requireFinite;

namespace {

/// C with its lower triangle copied from the upper one (exactly symmetric).
Eigen::Matrix3d symmetrized(Eigen::Matrix3d C)
{
    C.triangularView<Eigen::StrictlyLower>() = C.transpose();
    return C;
}

}  // namespace

CViewMap::TMapDefinition::TMapDefinition() = default;

void CViewMap::TMapDefinition::loadFromConfigFile_map_specific(
    const mrpt::config::CConfigFileBase& source, const std::string& sectionNamePrefix)
{
    renderOpts.loadFromConfigFile(source, sectionNamePrefix + "_renderOpts");
}

void CViewMap::TMapDefinition::dumpToTextStream_map_specific(std::ostream& out) const
{
    renderOpts.dumpToTextStream(out);
}

mrpt::maps::CMetricMap* CViewMap::internal_CreateFromMapDefinition(
    const mrpt::maps::TMetricMapInitializer& def)
{
    const auto& d = dynamic_cast<const CViewMap::TMapDefinition&>(def);
    auto* map = new CViewMap;
    map->renderOptions = d.renderOpts;
    return map;
}

void CViewMap::TRenderOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                  const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(draw_ellipses, bool, cfg, section);
    MRPT_LOAD_CONFIG_VAR(ellipse_quantiles, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(view_size, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(draw_ids, bool, cfg, section);
    requireKey(ellipse_quantiles > 0 && std::isfinite(ellipse_quantiles), section,
               "ellipse_quantiles", "must be finite and > 0");
    requireKey(view_size > 0 && std::isfinite(view_size), section, "view_size",
               "must be finite and > 0");
}

void CViewMap::TRenderOptions::dumpToTextStream(std::ostream& out) const
{
    out << "\n----------- [CViewMap::TRenderOptions] ------------ \n\n";
    LOADABLEOPTS_DUMP_VAR(draw_ellipses, bool);
    LOADABLEOPTS_DUMP_VAR(ellipse_quantiles, double);
    LOADABLEOPTS_DUMP_VAR(view_size, double);
    LOADABLEOPTS_DUMP_VAR(draw_ids, bool);
}

void CViewMap::checkView(const TView& v, const std::string& what)
{
    requireFinite(v.pose, what + ": pose");
    requireCovariance(v.covariance, false, what + ": covariance");
    const auto n = static_cast<Eigen::Index>(v.features.size());
    const TViewFeatures& f = v.features;
    if (f.pixels.cols() != n || static_cast<Eigen::Index>(f.scales.size()) != n ||
        static_cast<Eigen::Index>(f.laplacian_signs.size()) != n || f.rays.cols() != n)
        throw std::invalid_argument(what + ": feature arrays of different lengths");
}

size_t CViewMap::addView(TView view)
{
    checkView(view, "CViewMap::addView");
    view.id = static_cast<uint32_t>(m_views.size());
    view.covariance = symmetrized(view.covariance);
    m_views.push_back(std::move(view));
    return m_views.size() - 1;
}

const TView& CViewMap::view(size_t i) const
{
    if (i >= m_views.size())
        throw std::out_of_range(
            mrpt::format("CViewMap::view: index %zu out of range (size %zu)", i, m_views.size()));
    return m_views[i];
}

void CViewMap::setViewEstimate(size_t i, const mrpt::math::TPose2D& pose,
                               const Eigen::Matrix3d& covariance)
{
    const std::string what = mrpt::format("CViewMap::setViewEstimate(view %zu)", i);
    if (i >= m_views.size())
        throw std::invalid_argument(what + ": index out of range (size " +
                                    std::to_string(m_views.size()) + ")");
    requireFinite(pose, what + ": pose");
    requireCovariance(covariance, false, what + ": covariance");
    m_views[i].pose = pose;
    m_views[i].covariance = symmetrized(covariance);
}

bool CViewMap::isEmpty() const { return m_views.empty(); }

void CViewMap::internal_clear() { m_views.clear(); }

bool CViewMap::internal_insertObservation(const mrpt::obs::CObservation&,
                                          const std::optional<const mrpt::poses::CPose3D>&)
{
    return false;
}

bool CViewMap::internal_canComputeObservationLikelihood(const mrpt::obs::CObservation&) const
{
    return false;
}

double CViewMap::internal_computeObservationLikelihood(const mrpt::obs::CObservation&,
                                                       const mrpt::poses::CPose3D&) const
{
    return 0;
}

float CViewMap::compute3DMatchingRatio(const mrpt::maps::CMetricMap*, const mrpt::poses::CPose3D&,
                                       const mrpt::maps::TMatchingRatioParams&) const
{
    return 0;
}

void CViewMap::saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const
{
    core::AtomicFile views_file(filNamePrefix + "_views.txt");
    std::ostream& out = views_file.stream();
    out << "# views of the view map (CViewMap): timestamp [s], number of feature points, image "
           "file ('-' if none)\n# id timestamp features image_file\n";
    core::LandmarkFile file;
    file.is_view_map = true;
    for (const TView& v : m_views) {
        core::TLandmark out_view;
        out_view.id = static_cast<int>(v.id);
        out_view.position = {v.pose.x, v.pose.y, 0};
        out_view.yaw = v.pose.phi;
        out_view.cov = v.covariance;
        out_view.has_cov = true;
        file.landmarks.push_back(out_view);
        out << mrpt::format("%u %.6f %zu %s\n", v.id, v.timestamp, v.features.size(),
                            v.image_file.empty() ? "-" : v.image_file.c_str());
    }
    file.save(filNamePrefix + ".txt", "view map (CViewMap): yaw [rad], covariance of (x, y, yaw)");
    views_file.commit();
}

void CViewMap::getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const
{
    if (!genericMapParams.enableSaveAs3DObject || m_views.empty()) return;
    // One triangle per view in the XY plane, its centroid on the view and its tip along yaw.
    auto marks = mrpt::opengl::CSetOfTriangles::Create();
    marks->setName("views");
    const double L = renderOptions.view_size;
    for (const TView& v : m_views) {
        const double c = std::cos(v.pose.phi), s = std::sin(v.pose.phi);
        const auto at = [&](double ahead, double left) {
            return mrpt::math::TPoint3Df(static_cast<float>(v.pose.x + ahead * c - left * s),
                                         static_cast<float>(v.pose.y + ahead * s + left * c), 0);
        };
        marks->insertTriangle(
            mrpt::opengl::TTriangle(at(2 * L / 3, 0), at(-L / 3, L / 3), at(-L / 3, -L / 3)));
        const Eigen::Matrix2d xy = v.covariance.topLeftCorner<2, 2>();
        const bool positive_definite =
            xy.allFinite() && xy(0, 0) > 0 && xy(0, 0) * xy(1, 1) - xy(0, 1) * xy(1, 0) > 0;
        if (renderOptions.draw_ellipses && positive_definite) {
            auto ellipse = mrpt::opengl::CEllipsoid2D::Create();
            ellipse->setCovMatrix(mrpt::math::CMatrixDouble22(xy));
            ellipse->setQuantiles(static_cast<float>(renderOptions.ellipse_quantiles));
            ellipse->setLocation(v.pose.x, v.pose.y, 0);
            ellipse->setColor(0.1f, 0.3f, 1.0f, 0.6f);
            ellipse->setName(mrpt::format("view_%u", v.id));
            o.insert(ellipse);
        }
        if (renderOptions.draw_ids) {
            auto label = mrpt::opengl::CText::Create(std::to_string(v.id));
            label->setLocation(v.pose.x, v.pose.y, 0.1);
            o.insert(label);
        }
    }
    // after the triangles: setColor() recolours those present, new ones come in black
    marks->setColor(0.1f, 0.3f, 1.0f);
    o.insert(marks);
}

std::string CViewMap::asString() const
{
    size_t points = 0;
    for (const TView& v : m_views) points += v.features.size();
    std::ostringstream s;
    s << "CViewMap: " << m_views.size() << " views, " << points << " feature points";
    return s.str();
}

}  // namespace mrpt_vslam::viewmap
