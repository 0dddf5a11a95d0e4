#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/img/CImage.h>
#include <mrpt/poses/CPose3D.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/viewmap/COmniViewSLAM.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mrpt_vslam::viewmap {

using core::requireOption;

namespace {
Eigen::Matrix3d initialCovariance(const COmniViewSLAM::TOptions& o)
{
    const double s2 = o.initial_sigma_xy * o.initial_sigma_xy;
    return Eigen::Vector3d(s2, s2, o.initial_sigma_yaw * o.initial_sigma_yaw).asDiagonal();
}
}  // namespace

void COmniViewSLAM::TOptions::validate() const
{
    requireOption(candidate_distance > 0 && std::isfinite(candidate_distance), "candidate_distance",
                  "must be finite and > 0");
    requireOption(max_candidates >= 1, "max_candidates", "must be >= 1");
    requireOption(min_baseline > 0 && min_baseline < candidate_distance, "min_baseline",
                  "must be > 0 and < candidate_distance");
    requireOption(gate_probability > 0 && gate_probability < 1, "gate_probability",
                  "must be in (0, 1)");
    requireOption(initial_sigma_xy > 0 && std::isfinite(initial_sigma_xy), "initial_sigma_xy",
                  "must be finite and > 0");
    requireOption(initial_sigma_yaw > 0 && std::isfinite(initial_sigma_yaw),
                  "initial_sigma_yaw_deg", "must be finite and > 0");
}

void COmniViewSLAM::TOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                 const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(candidate_distance, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_candidates, int, cfg, section);
    MRPT_LOAD_CONFIG_VAR(min_baseline, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(gate_probability, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(initial_sigma_xy, double, cfg, section);
    initial_sigma_yaw = mrpt::DEG2RAD(
        cfg.read_double(section, "initial_sigma_yaw_deg", mrpt::RAD2DEG(initial_sigma_yaw)));
    try {
        validate();
    } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("[" + section + "] " + e.what());
    }
}

void COmniViewSLAM::TOptions::saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                                               const std::string& section) const
{
    MRPT_SAVE_CONFIG_VAR(candidate_distance, cfg, section);
    MRPT_SAVE_CONFIG_VAR(max_candidates, cfg, section);
    MRPT_SAVE_CONFIG_VAR(min_baseline, cfg, section);
    MRPT_SAVE_CONFIG_VAR(gate_probability, cfg, section);
    MRPT_SAVE_CONFIG_VAR(initial_sigma_xy, cfg, section);
    cfg.write(section, "initial_sigma_yaw_deg", mrpt::RAD2DEG(initial_sigma_yaw));
}

size_t COmniViewSLAM::TStepResult::accepted() const
{
    return size_t(std::count_if(observations.begin(), observations.end(),
                                [](const auto& o) { return o.accepted; }));
}

COmniViewSLAM::COmniViewSLAM(const TOptions& options, OmniFeatureExtractor extractor,
                             const OmniViewObserver::TOptions& observer,
                             const ViewInitializationPolicy::TOptions& policy, uint32_t seed)
    : m_options(options),
      m_extractor(std::move(extractor)),
      m_observer(observer),
      m_policy_options(policy),
      m_seed(seed),
      m_ekf(mrpt::math::TPose2D(0, 0, 0))
{
    m_options.validate();
    // χ²₂ quantile in closed form: −2 ln(1 − p).
    m_gate = -2 * std::log(1 - m_options.gate_probability);
    reset(mrpt::math::TPose2D(0, 0, 0));
}

std::unique_ptr<COmniViewSLAM> COmniViewSLAM::fromConfig(const mrpt::config::CConfigFileBase& cfg,
                                                         uint32_t seed)
{
    TOptions options;
    options.loadFromConfigFile(cfg, "ViewSLAM");
    core::UnifiedSphereCamera camera;
    camera.loadFromConfigFile(cfg, "Camera");
    // The rotation and the horizontal position: the height does not change a bearing between
    // camera centres or a relative heading.
    bool configured = false;
    const auto value = [&](const char* key) {
        if (!cfg.keyExists("CameraOnRobot", key)) return 0.0;
        configured = true;
        const double v = cfg.read_double("CameraOnRobot", key, 0);
        if (!std::isfinite(v))
            throw std::invalid_argument(std::string("[CameraOnRobot] ") + key + ": not finite");
        return v;
    };
    const double x = value("x"), y = value("y");
    const double yaw = mrpt::DEG2RAD(value("yaw_deg")), pitch = mrpt::DEG2RAD(value("pitch_deg")),
                 roll = mrpt::DEG2RAD(value("roll_deg"));
    const Eigen::Matrix3d cameraToRobot =
        mrpt::poses::CPose3D(0, 0, 0, yaw, pitch, roll).getRotationMatrix().asEigen();
    OmniFeatureExtractor::TOptions features = filterFeatureOptions();
    features.loadFromConfigFile(cfg, "Features");
    OmniViewObserver::TOptions observer = filterObserverOptions();
    observer.loadFromConfigFile(cfg, "ViewObserver");
    ViewInitializationPolicy::TOptions policy;
    policy.loadFromConfigFile(cfg, "ViewInitialization");
    auto slam = std::make_unique<COmniViewSLAM>(
        options, OmniFeatureExtractor(camera, cameraToRobot, features), observer, policy, seed);
    slam->m_camera_on_robot_configured = configured;
    slam->m_ekf.setCameraPosition({x, y});
    return slam;
}

OmniFeatureExtractor::TOptions COmniViewSLAM::filterFeatureOptions()
{
    OmniFeatureExtractor::TOptions o;
    o.detector.hessian_threshold = 30;
    return o;
}

OmniViewObserver::TOptions COmniViewSLAM::filterObserverOptions()
{
    OmniViewObserver::TOptions o;
    o.matching.max_descriptor_distance = 0.6;
    o.ransac.min_inliers = 20;
    o.min_sigma_phi = mrpt::DEG2RAD(1.5);
    o.min_sigma_beta = mrpt::DEG2RAD(0.75);
    return o;
}

void COmniViewSLAM::useCameraPoseOf(const mrpt::poses::CPose3D& camera_on_robot)
{
    if (m_camera_on_robot_configured) return;
    m_extractor.setCameraToRobot(camera_on_robot.getRotationMatrix().asEigen());
    m_ekf.setCameraPosition({camera_on_robot.x(), camera_on_robot.y()});
}

void COmniViewSLAM::reset(const mrpt::math::TPose2D& start)
{
    const mrpt::math::TPoint2D camera = m_ekf.cameraPosition();
    m_ekf = ViewMapEKF(start, initialCovariance(m_options));
    m_ekf.setCameraPosition(camera);
    m_map.clear();
    m_policy = ViewInitializationPolicy::create(m_policy_options);
    m_rng.randomize(m_seed);
}

std::vector<size_t> COmniViewSLAM::candidateViews() const
{
    const auto robot = m_ekf.robotPose();
    std::vector<std::pair<double, size_t>> near;
    for (size_t i = 0; i < m_ekf.viewCount(); i++) {
        const auto v = m_ekf.viewPose(i);
        const double d = std::hypot(v.x - robot.x, v.y - robot.y);
        if (d >= m_options.min_baseline && d <= m_options.candidate_distance)
            near.emplace_back(d, i);
    }
    std::sort(near.begin(), near.end());
    if (near.size() > size_t(m_options.max_candidates))
        near.resize(size_t(m_options.max_candidates));
    std::vector<size_t> views;
    for (const auto& n : near) views.push_back(n.second);
    return views;
}

COmniViewSLAM::TStepResult COmniViewSLAM::processStep(const mrpt::math::TPose2D& increment,
                                                      const Eigen::Matrix3d& Q,
                                                      const mrpt::img::CImage* image,
                                                      double timestamp,
                                                      const std::string& image_file)
{
    // a bad image is refused before anything changes
    if (image && image->isEmpty()) throw std::invalid_argument("COmniViewSLAM: empty image");
    TStepResult result;
    TViewPolicyInputs in;
    in.ekf = &m_ekf;
    // Step 1.
    in.P_vv_previous = m_ekf.robotCovariance();
    m_ekf.predict(increment, Q);
    in.P_vv_predicted = m_ekf.robotCovariance();
    if (!image) return result;

    // Step 2.
    TViewFeatures features = m_extractor.extract(*image);
    result.features = features.size();
    in.features = &features;
    in.consistent.assign(features.size(), false);

    // Steps 3-4.
    for (const size_t view : candidateViews()) {
        TObservationRecord rec;
        rec.view = view;
        const auto predicted = m_ekf.predictObservation(view);
        const auto obs = m_observer.observe(features, m_map.view(view).features,
                                            {predicted.z, predicted.HPHt}, m_rng);
        if (obs) {
            rec.estimated = true;
            rec.matches = obs->matches;
            rec.inliers = obs->inliers;
            rec.z = obs->z;
            rec.R = obs->R;
            const auto upd = m_ekf.update(view, obs->z, obs->R, m_gate);
            rec.nis = upd.nis;
            rec.accepted = upd.accepted;
            if (upd.accepted) {
                for (const uint32_t k : obs->inlier_current) in.consistent[k] = true;
                in.observed.push_back({view, obs->R, obs->inliers});
            }
        }
        result.observations.push_back(rec);
    }

    // Step 5.
    const auto robot = m_ekf.robotPose();
    for (size_t i = 0; i < m_ekf.viewCount(); i++) {
        const auto v = m_ekf.viewPose(i);
        in.nearest_view_distance =
            std::min(in.nearest_view_distance, std::hypot(v.x - robot.x, v.y - robot.y));
    }
    result.decision = m_policy->decide(in, m_rng);
    if (result.decision.add && !features.empty()) {
        const size_t index = m_ekf.addView();
        TView view;
        view.pose = robot;
        view.covariance = m_ekf.viewCovariance(index);
        view.timestamp = timestamp;
        view.image_file = image_file;
        view.features = std::move(features);
        m_map.addView(std::move(view));
        result.new_view = index;
    }
    return result;
}

const CViewMap& COmniViewSLAM::map()
{
    for (size_t i = 0; i < m_ekf.viewCount(); i++)
        m_map.setViewEstimate(i, m_ekf.viewPose(i), m_ekf.viewCovariance(i));
    return m_map;
}

}  // namespace mrpt_vslam::viewmap
