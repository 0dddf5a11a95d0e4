#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/obs/CObservationBearingRange.h>
#include <mrpt/opengl/CEllipsoid3D.h>
#include <mrpt/opengl/CPointCloud.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt/opengl/CSphere.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <algorithm>
#include <limits>
#include <sstream>

using mrpt_vslam::omni_fastslam::CCeilingLightsMap;

MAP_DEFINITION_REGISTER("mrpt_vslam::omni_fastslam::CCeilingLightsMap,ceilingLightsMap",
                        mrpt_vslam::omni_fastslam::CCeilingLightsMap)

IMPLEMENTS_SERIALIZABLE(CCeilingLightsMap, mrpt::maps::CMetricMap, mrpt_vslam::omni_fastslam)

namespace mrpt_vslam::omni_fastslam {

CCeilingLightsMap::TMapDefinition::TMapDefinition() = default;

void CCeilingLightsMap::TMapDefinition::loadFromConfigFile_map_specific(
    const mrpt::config::CConfigFileBase& source, const std::string& sectionNamePrefix)
{
    sensorOpts.loadFromConfigFile(source, sectionNamePrefix + "_creationOpts");
    insertionOpts.loadFromConfigFile(source, sectionNamePrefix + "_insertOpts");
    likelihoodOpts.loadFromConfigFile(source, sectionNamePrefix + "_likelihoodOpts");
    renderOpts.loadFromConfigFile(source, sectionNamePrefix + "_renderOpts");
}

void CCeilingLightsMap::TMapDefinition::dumpToTextStream_map_specific(std::ostream& out) const
{
    sensorOpts.dumpToTextStream(out);
    insertionOpts.dumpToTextStream(out);
    likelihoodOpts.dumpToTextStream(out);
    renderOpts.dumpToTextStream(out);
}

mrpt::maps::CMetricMap* CCeilingLightsMap::internal_CreateFromMapDefinition(
    const mrpt::maps::TMetricMapInitializer& def)
{
    const auto& d = dynamic_cast<const CCeilingLightsMap::TMapDefinition&>(def);
    auto* map = new CCeilingLightsMap;
    map->sensorOptions = d.sensorOpts;
    map->insertionOptions = d.insertionOpts;
    map->likelihoodOptions = d.likelihoodOpts;
    map->renderOptions = d.renderOpts;
    return map;
}

int64_t CCeilingLightsMap::addLandmark(const Eigen::Vector3d& mean, const Eigen::Matrix3d& cov,
                                       TLandmarkType type, int counter)
{
    TLightLandmark lm;
    lm.id = m_next_landmark_id++;
    lm.mean = mean;
    lm.cov = 0.5 * (cov + cov.transpose());
    lm.type = type;
    lm.counter = counter;
    m_landmarks.push_back(lm);
    return lm.id;
}

CCeilingLightsMap::TSensorLimits CCeilingLightsMap::sensorLimitsInUse() const
{
    return limitsInUse(m_observed_limits);
}

CCeilingLightsMap::TSensorLimits CCeilingLightsMap::limitsInUse(const TSensorLimits& observed) const
{
    TSensorLimits limits;
    limits.max_abs_azimuth = sensorOptions.max_abs_azimuth.value_or(observed.max_abs_azimuth);
    limits.min_range = insertionOptions.min_cross_point_range.value_or(observed.min_range);
    limits.max_range = insertionOptions.max_cross_point_range.value_or(observed.max_range);
    return limits;
}

BearingMeasurementModel CCeilingLightsMap::measurementModel() const
{
    return BearingMeasurementModel(m_sensor_in_robot, sensorOptions.measurement_model);
}

void CCeilingLightsMap::internal_clear()
{
    m_landmarks.clear();
    m_candidates.clear();
    m_step = 0;
    m_next_landmark_id = 0;
    m_next_candidate_id = 0;
}

bool CCeilingLightsMap::isEmpty() const { return m_landmarks.empty() && m_candidates.empty(); }

bool CCeilingLightsMap::internal_insertObservation(
    const mrpt::obs::CObservation& obs, const std::optional<const mrpt::poses::CPose3D>& robotPose)
{
    const auto* br = dynamic_cast<const mrpt::obs::CObservationBearingRange*>(&obs);
    if (!br) return false;
    const mrpt::poses::CPose3D robot = robotPose ? *robotPose : mrpt::poses::CPose3D();
    insertMeasurements(measurementsFromObservation(*br),
                       mrpt::math::TPose2D(robot.x(), robot.y(), robot.yaw()));
    return true;
}

bool CCeilingLightsMap::internal_canComputeObservationLikelihood(
    const mrpt::obs::CObservation& obs) const
{
    return dynamic_cast<const mrpt::obs::CObservationBearingRange*>(&obs) != nullptr;
}

double CCeilingLightsMap::internal_computeObservationLikelihood(
    const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const
{
    const auto* br = dynamic_cast<const mrpt::obs::CObservationBearingRange*>(&obs);
    if (!br) return 0;
    const mrpt::math::TPose2D robot(takenFrom.x(), takenFrom.y(), takenFrom.yaw());
    const auto z = measurementsFromObservation(*br);
    const Eigen::MatrixXd log_phi = landmarkLogLikelihoods(z, robot);

    // Each measurement: its most likely landmark, floored by P_new (spurious detections)
    std::vector<bool> seen(m_landmarks.size(), false);
    double log_lik = 0;
    for (size_t l = 0; l < z.size(); l++) {
        double best = logPNew(z[l]);
        int best_j = -1;
        for (size_t j = 0; j < m_landmarks.size(); j++) {
            if (usesForWeight(m_landmarks[j]) && log_phi(l, j) > best) {
                best = log_phi(l, j);
                best_j = static_cast<int>(j);
            }
        }
        if (best_j >= 0) seen[best_j] = true;
        log_lik += best;
    }
    // Unseen landmarks inside the perceptual range: 1 − p_in each (Alg. 4 line 21)
    if (likelihoodOptions.p_in > 0) {
        const double log_miss = std::log(1 - likelihoodOptions.p_in);
        const auto model = measurementModel();
        const auto at = model.atPose(robot);
        for (size_t j = 0; j < m_landmarks.size(); j++)
            if (!seen[j] && usesForWeight(m_landmarks[j]) &&
                isInPerceptualRange(m_landmarks[j].mean, at))
                log_lik += log_miss;
    }
    return log_lik;
}

float CCeilingLightsMap::compute3DMatchingRatio(const mrpt::maps::CMetricMap*,
                                                const mrpt::poses::CPose3D&,
                                                const mrpt::maps::TMatchingRatioParams&) const
{
    return 0;  // not defined for bearing-only landmark maps
}

void CCeilingLightsMap::saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const
{
    core::LandmarkFile file;
    for (const auto& lm : m_landmarks) {
        core::TLandmark out;
        out.id = static_cast<int>(lm.id);
        out.position = {lm.mean.x(), lm.mean.y(), lm.mean.z()};
        out.cov = lm.cov;
        out.has_cov = true;
        file.landmarks.push_back(out);
    }
    file.save(filNamePrefix + ".txt", "omni FastSLAM ceiling-lights map (CCeilingLightsMap)");
}

void CCeilingLightsMap::getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const
{
    if (!genericMapParams.enableSaveAs3DObject) return;
    for (const auto& lm : m_landmarks) {
        const bool type_i = lm.type == TLandmarkType::TypeI;
        const mrpt::img::TColorf colour =
            type_i ? mrpt::img::TColorf(0.1f, 0.3f, 1.0f) : mrpt::img::TColorf(1.0f, 0.5f, 0.0f);
        auto ellipsoid = mrpt::opengl::CEllipsoid3D::Create();
        ellipsoid->setCovMatrixAndMean(mrpt::math::CMatrixDouble33(lm.cov),
                                       mrpt::math::CMatrixFixed<double, 3, 1>(lm.mean));
        ellipsoid->setQuantiles(static_cast<float>(renderOptions.ellipsoid_quantiles));
        ellipsoid->setColor(colour.R, colour.G, colour.B, 0.6f);
        ellipsoid->setName(mrpt::format("light_%ld", static_cast<long>(lm.id)));
        o.insert(ellipsoid);
        auto sphere = mrpt::opengl::CSphere::Create(0.05f);
        sphere->setLocation(lm.mean.x(), lm.mean.y(), lm.mean.z());
        sphere->setColor(colour.R, colour.G, colour.B);
        o.insert(sphere);
    }
    if (!renderOptions.draw_candidates) return;
    auto cloud = mrpt::opengl::CPointCloud::Create();
    cloud->setPointSize(3.0f);
    cloud->setColor(0.5f, 0.5f, 0.5f, 0.35f);
    for (const auto& cand : m_candidates) {
        const auto best = std::max_element(
            cand.cross_points.begin(), cand.cross_points.end(),
            [](const auto& a, const auto& b) { return a.sum_log_prob < b.sum_log_prob; });
        if (best != cand.cross_points.end())
            cloud->insertPoint(static_cast<float>(best->point.x()),
                               static_cast<float>(best->point.y()),
                               static_cast<float>(best->point.z()));
    }
    o.insert(cloud);
}

std::string CCeilingLightsMap::asString() const
{
    const auto n_type_i = std::count_if(m_landmarks.begin(), m_landmarks.end(), [](const auto& l) {
        return l.type == TLandmarkType::TypeI;
    });
    std::ostringstream s;
    s << "CCeilingLightsMap: " << m_landmarks.size() << " landmarks (" << n_type_i << " type I, "
      << (static_cast<long>(m_landmarks.size()) - n_type_i) << " type II), " << m_candidates.size()
      << " candidates, step " << m_step;
    return s.str();
}

bool CCeilingLightsMap::usesForWeight(const TLightLandmark& lm) const
{
    return lm.type == TLandmarkType::TypeI || likelihoodOptions.use_type_ii_landmarks;
}

}  // namespace mrpt_vslam::omni_fastslam
