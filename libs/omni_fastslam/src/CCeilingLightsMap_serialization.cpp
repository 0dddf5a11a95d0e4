#include <mrpt/serialization/CArchive.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

namespace mrpt_vslam::omni_fastslam {

namespace {
using mrpt::serialization::CArchive;

template <typename Derived>
void writeMatrix(CArchive& out, const Eigen::MatrixBase<Derived>& m)
{
    for (int r = 0; r < m.rows(); r++)
        for (int c = 0; c < m.cols(); c++) out << static_cast<double>(m(r, c));
}

template <typename Derived>
void readMatrix(CArchive& in, Eigen::MatrixBase<Derived>& m)
{
    for (int r = 0; r < m.rows(); r++)
        for (int c = 0; c < m.cols(); c++) in >> m(r, c);
}

void writePose2D(CArchive& out, const mrpt::math::TPose2D& p) { out << p.x << p.y << p.phi; }
void readPose2D(CArchive& in, mrpt::math::TPose2D& p) { in >> p.x >> p.y >> p.phi; }

void writePose3D(CArchive& out, const mrpt::poses::CPose3D& p)
{
    out << p.x() << p.y() << p.z() << p.yaw() << p.pitch() << p.roll();
}
void readPose3D(CArchive& in, mrpt::poses::CPose3D& p)
{
    double x, y, z, yaw, pitch, roll;
    in >> x >> y >> z >> yaw >> pitch >> roll;
    p = mrpt::poses::CPose3D(x, y, z, yaw, pitch, roll);
}

void writeLandmark(CArchive& out, const TLightLandmark& lm)
{
    out << lm.id;
    writeMatrix(out, lm.mean);
    writeMatrix(out, lm.cov);
    out << static_cast<int32_t>(lm.counter) << static_cast<uint8_t>(lm.type)
        << static_cast<int32_t>(lm.consecutive_close);
}

void readLandmark(CArchive& in, TLightLandmark& lm)
{
    int32_t counter, close;
    uint8_t type;
    in >> lm.id;
    readMatrix(in, lm.mean);
    readMatrix(in, lm.cov);
    in >> counter >> type >> close;
    if (type != static_cast<uint8_t>(TLandmarkType::TypeI) &&
        type != static_cast<uint8_t>(TLandmarkType::TypeII))
        THROW_EXCEPTION_FMT("CCeilingLightsMap: invalid landmark type %u", type);
    lm.counter = counter;
    lm.type = static_cast<TLandmarkType>(type);
    lm.consecutive_close = close;
}

void writeCandidate(CArchive& out, const TCandidateLight& c)
{
    out << c.id << static_cast<int32_t>(c.counter) << static_cast<int32_t>(c.consecutive_misses)
        << c.nz << static_cast<uint32_t>(c.observations.size());
    for (const auto& o : c.observations) {
        writeMatrix(out, o.measurement.z);
        writeMatrix(out, o.measurement.Q);
        writePose2D(out, o.robot_in_map);
        out << o.step;
    }
    out << c.depth_min << c.depth_max;  // version 1
    out << static_cast<uint32_t>(c.cross_points.size());
    for (const auto& x : c.cross_points) {
        writeMatrix(out, x.point);
        out << x.step_first << x.step_second << x.angle << x.gap << x.in_front << x.sum_log_prob
            << x.sum_mahalanobis2 << x.valid;
    }
}

void readCandidate(CArchive& in, TCandidateLight& c, uint8_t version)
{
    int32_t counter, misses;
    uint32_t n;
    in >> c.id >> counter >> misses >> c.nz >> n;
    c.counter = counter;
    c.consecutive_misses = misses;
    c.observations.resize(n);
    for (auto& o : c.observations) {
        readMatrix(in, o.measurement.z);
        readMatrix(in, o.measurement.Q);
        readPose2D(in, o.robot_in_map);
        in >> o.step;
    }
    c.depth_min = c.depth_max = 0;
    if (version >= 1) in >> c.depth_min >> c.depth_max;
    in >> n;
    c.cross_points.resize(n);
    for (auto& x : c.cross_points) {
        readMatrix(in, x.point);
        in >> x.step_first >> x.step_second >> x.angle >> x.gap >> x.in_front >> x.sum_log_prob >>
            x.sum_mahalanobis2 >> x.valid;
    }
}
}  // namespace

uint8_t CCeilingLightsMap::serializeGetVersion() const { return 3; }

void CCeilingLightsMap::serializeTo(mrpt::serialization::CArchive& out) const
{
    out << genericMapParams;
    // Options travel with the map: CMultiMetricMap copies (particle resampling) serialize it.
    writePose3D(out, m_sensor_in_robot);
    out << sensorOptions.sigma_phi << sensorOptions.sigma_theta << sensorOptions.max_theta
        << sensorOptions.max_horizontal_distance;
    const auto& io = insertionOptions;
    out << static_cast<uint8_t>(io.association_method) << static_cast<uint32_t>(io.nz_min)
        << static_cast<uint32_t>(io.ncross_valid) << io.ang_min << io.d_min << io.sigma0_xx
        << io.sigma0_yy << io.sigma0_zz << io.p_new_mahalanobis2
        << static_cast<uint32_t>(io.candidate_miss_decrement)
        << static_cast<uint32_t>(io.max_candidate_measurements) << io.refine_initialization;
    out << likelihoodOptions.p_in << likelihoodOptions.use_type_ii_landmarks;
    out << renderOptions.draw_candidates << renderOptions.ellipsoid_quantiles;
    // version 1: the measurement model and its perceptual and cross-point limits (in use)
    const TSensorLimits limits = sensorLimitsInUse();
    out << static_cast<uint8_t>(sensorOptions.measurement_model) << limits.max_abs_azimuth
        << limits.max_range << limits.min_range << static_cast<uint32_t>(io.hit_increment);
    // version 2: whether that pose is the config's (else the last observation's)
    out << sensorOptions.sensor_in_robot.has_value();
    // version 3: which of those limits are the config's, and the last observation's
    out << sensorOptions.max_abs_azimuth.has_value() << io.max_cross_point_range.has_value()
        << io.min_cross_point_range.has_value() << m_observed_limits.max_abs_azimuth
        << m_observed_limits.max_range << m_observed_limits.min_range;

    out << m_step << m_next_landmark_id << m_next_candidate_id;
    out << static_cast<uint32_t>(m_landmarks.size());
    for (const auto& lm : m_landmarks) writeLandmark(out, lm);
    out << static_cast<uint32_t>(m_candidates.size());
    for (const auto& c : m_candidates) writeCandidate(out, c);
}

void CCeilingLightsMap::serializeFrom(mrpt::serialization::CArchive& in, uint8_t version)
{
    switch (version) {
        case 0:
        case 1:
        case 2:
        case 3: {
            in >> genericMapParams;
            readPose3D(in, m_sensor_in_robot);
            in >> sensorOptions.sigma_phi >> sensorOptions.sigma_theta >> sensorOptions.max_theta >>
                sensorOptions.max_horizontal_distance;
            auto& io = insertionOptions;
            uint8_t method;
            uint32_t nz_min, ncross, miss_dec, max_meas;
            in >> method >> nz_min >> ncross >> io.ang_min >> io.d_min >> io.sigma0_xx >>
                io.sigma0_yy >> io.sigma0_zz >> io.p_new_mahalanobis2 >> miss_dec >> max_meas >>
                io.refine_initialization;
            if (method > static_cast<uint8_t>(TAssociationMethod::ML))
                THROW_EXCEPTION_FMT("CCeilingLightsMap: invalid association method %u", method);
            io.association_method = static_cast<TAssociationMethod>(method);
            io.nz_min = nz_min;
            io.ncross_valid = ncross;
            io.candidate_miss_decrement = miss_dec;
            io.max_candidate_measurements = max_meas;
            in >> likelihoodOptions.p_in >> likelihoodOptions.use_type_ii_landmarks;
            in >> renderOptions.draw_candidates >> renderOptions.ellipsoid_quantiles;
            sensorOptions.measurement_model = TMeasurementModelKind::Spherical;
            TSensorLimits limits;  // before version 1: all around, no range limit
            io.hit_increment = 1;
            if (version >= 1) {
                uint8_t kind;
                uint32_t hit;
                in >> kind >> limits.max_abs_azimuth >> limits.max_range >> limits.min_range >> hit;
                io.hit_increment = hit;
                if (kind > static_cast<uint8_t>(TMeasurementModelKind::Planar))
                    THROW_EXCEPTION_FMT("CCeilingLightsMap: invalid measurement model %u", kind);
                sensorOptions.measurement_model = static_cast<TMeasurementModelKind>(kind);
            }
            bool configured = true;  // before version 2 the pose was always the config's
            if (version >= 2) in >> configured;
            sensorOptions.sensor_in_robot.reset();
            if (configured) sensorOptions.sensor_in_robot = m_sensor_in_robot;
            // before version 3 the limits were always the config's
            bool azimuth_set = true, max_set = true, min_set = true;
            m_observed_limits = TSensorLimits();
            if (version >= 3)
                in >> azimuth_set >> max_set >> min_set >> m_observed_limits.max_abs_azimuth >>
                    m_observed_limits.max_range >> m_observed_limits.min_range;
            sensorOptions.max_abs_azimuth.reset();
            io.max_cross_point_range.reset();
            io.min_cross_point_range.reset();
            if (azimuth_set) sensorOptions.max_abs_azimuth = limits.max_abs_azimuth;
            if (max_set) io.max_cross_point_range = limits.max_range;
            if (min_set) io.min_cross_point_range = limits.min_range;

            uint32_t n;
            in >> m_step >> m_next_landmark_id >> m_next_candidate_id >> n;
            m_landmarks.resize(n);
            for (auto& lm : m_landmarks) readLandmark(in, lm);
            in >> n;
            m_candidates.resize(n);
            for (auto& c : m_candidates) readCandidate(in, c, version);
        } break;
        default:
            MRPT_THROW_UNKNOWN_SERIALIZATION_VERSION(version);
    }
}

}  // namespace mrpt_vslam::omni_fastslam
