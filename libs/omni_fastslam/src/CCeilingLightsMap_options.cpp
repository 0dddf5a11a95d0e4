#include <mrpt/config/CConfigFileBase.h>
#include <mrpt/core/bits_math.h>
#include <mrpt/core/format.h>
#include <mrpt_vslam/core/ConfigChoice.h>
#include <mrpt_vslam/core/OptionChecks.h>
#include <mrpt_vslam/omni_fastslam/CCeilingLightsMap.h>

#include <cmath>
#include <ostream>

namespace mrpt_vslam::omni_fastslam {

using core::requireKey;

namespace {
/// A key whose empty value (or absence) means "the observation's own": unset, else its number
/// times `unit`.
std::optional<double> readOptionalDouble(const mrpt::config::CConfigFileBase& cfg,
                                         const std::string& section, const std::string& key,
                                         double unit)
{
    if (cfg.read_string(section, key, "").empty()) return std::nullopt;
    return unit * cfg.read_double(section, key, 0);
}

/// An optional value for dumpToTextStream(): the number, or whose it is when unset.
std::string optionalText(const std::optional<double>& v, double unit)
{
    return v ? mrpt::format("%g", *v / unit) : "(each observation's own)";
}
}  // namespace

void CCeilingLightsMap::TSensorOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                           const std::string& section)
{
    measurement_model = core::readEnum(cfg, section, "measurement_model", measurement_model);
    if (const std::string text = cfg.read_string(section, "sensor_in_robot", ""); !text.empty()) {
        mrpt::poses::CPose3D pose;
        bool parsed = true;
        try {
            pose.fromString(text);
        } catch (const std::exception&) {
            parsed = false;
        }
        for (const double v : {pose.x(), pose.y(), pose.z(), pose.yaw(), pose.pitch(), pose.roll()})
            parsed = parsed && std::isfinite(v);
        requireKey(parsed, section, "sensor_in_robot",
                   ("expected [x y z yaw pitch roll] (m, deg), got '" + text + "'").c_str());
        sensor_in_robot = pose;
    }
    sigma_phi = mrpt::DEG2RAD(cfg.read_double(section, "sigma_phi_deg", mrpt::RAD2DEG(sigma_phi)));
    sigma_theta =
        mrpt::DEG2RAD(cfg.read_double(section, "sigma_theta_deg", mrpt::RAD2DEG(sigma_theta)));
    max_theta = mrpt::DEG2RAD(cfg.read_double(section, "max_theta_deg", mrpt::RAD2DEG(max_theta)));
    MRPT_LOAD_CONFIG_VAR(max_horizontal_distance, double, cfg, section);
    if (const auto v = readOptionalDouble(cfg, section, "max_abs_azimuth_deg", mrpt::DEG2RAD(1.0)))
        max_abs_azimuth = v;

    requireKey(sigma_phi > 0, section, "sigma_phi_deg", "must be > 0");
    requireKey(sigma_theta > 0, section, "sigma_theta_deg", "must be > 0");
    requireKey(max_theta > 0 && max_theta <= M_PI, section, "max_theta_deg", "must be in (0, 180]");
    requireKey(max_horizontal_distance >= 0, section, "max_horizontal_distance", "must be >= 0");
    requireKey(!max_abs_azimuth || (*max_abs_azimuth > 0 && *max_abs_azimuth <= M_PI), section,
               "max_abs_azimuth_deg", "must be in (0, 180], or empty for the observations' own");
}

void CCeilingLightsMap::TSensorOptions::dumpToTextStream(std::ostream& out) const
{
    out << "\n----------- [CCeilingLightsMap::TSensorOptions] ------------ \n\n";
    dumpVar_string(out, "measurement_model",
                   mrpt::typemeta::TEnumType<TMeasurementModelKind>::value2name(measurement_model));
    dumpVar_string(out, "sensor_in_robot",
                   sensor_in_robot ? sensor_in_robot->asString() : "(each observation's own)");
    dumpVar_double(out, "sigma_phi_deg", mrpt::RAD2DEG(sigma_phi));
    dumpVar_double(out, "sigma_theta_deg", mrpt::RAD2DEG(sigma_theta));
    dumpVar_double(out, "max_theta_deg", mrpt::RAD2DEG(max_theta));
    LOADABLEOPTS_DUMP_VAR(max_horizontal_distance, double);
    dumpVar_string(out, "max_abs_azimuth_deg", optionalText(max_abs_azimuth, mrpt::DEG2RAD(1.0)));
}

void CCeilingLightsMap::TInsertionOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
    association_method = core::readEnum(cfg, section, "association_method", association_method);
    MRPT_LOAD_CONFIG_VAR(nz_min, uint64_t, cfg, section);
    MRPT_LOAD_CONFIG_VAR(ncross_valid, uint64_t, cfg, section);
    ang_min = mrpt::DEG2RAD(cfg.read_double(section, "ang_min_deg", mrpt::RAD2DEG(ang_min)));
    MRPT_LOAD_CONFIG_VAR(d_min, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(sigma0_xx, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(sigma0_yy, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(sigma0_zz, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(p_new_mahalanobis2, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(candidate_miss_decrement, uint64_t, cfg, section);
    MRPT_LOAD_CONFIG_VAR(max_candidate_measurements, uint64_t, cfg, section);
    MRPT_LOAD_CONFIG_VAR(refine_initialization, bool, cfg, section);
    if (const auto v = readOptionalDouble(cfg, section, "max_cross_point_range", 1))
        max_cross_point_range = v;
    if (const auto v = readOptionalDouble(cfg, section, "min_cross_point_range", 1))
        min_cross_point_range = v;
    MRPT_LOAD_CONFIG_VAR(hit_increment, uint64_t, cfg, section);

    requireKey(nz_min >= 2, section, "nz_min", "must be >= 2 (two rays make a cross-point)");
    requireKey(ncross_valid >= 1, section, "ncross_valid", "must be >= 1");
    requireKey(ang_min >= 0 && ang_min < M_PI, section, "ang_min_deg", "must be in [0, 180)");
    requireKey(d_min > 0, section, "d_min", "must be > 0");
    requireKey(sigma0_xx > 0 && sigma0_yy > 0 && sigma0_zz > 0, section, "sigma0_xx/yy/zz",
               "must be > 0");
    requireKey(p_new_mahalanobis2 > 0, section, "p_new_mahalanobis2", "must be > 0");
    requireKey(max_candidate_measurements >= nz_min, section, "max_candidate_measurements",
               "must be >= nz_min");
    requireKey(max_cross_point_range.value_or(0) >= 0, section, "max_cross_point_range",
               "must be >= 0, or empty for the observations' own");
    requireKey(min_cross_point_range.value_or(0) >= 0 &&
                   (!min_cross_point_range || !max_cross_point_range ||
                    *max_cross_point_range == 0 || *min_cross_point_range < *max_cross_point_range),
               section, "min_cross_point_range",
               "must be >= 0 and < max_cross_point_range, or empty for the observations' own");
    requireKey(hit_increment >= 1, section, "hit_increment", "must be >= 1");
}

void CCeilingLightsMap::TInsertionOptions::dumpToTextStream(std::ostream& out) const
{
    out << "\n----------- [CCeilingLightsMap::TInsertionOptions] ------------ \n\n";
    dumpVar_string(out, "association_method",
                   mrpt::typemeta::TEnumType<TAssociationMethod>::value2name(association_method));
    LOADABLEOPTS_DUMP_VAR(nz_min, int);
    LOADABLEOPTS_DUMP_VAR(ncross_valid, int);
    dumpVar_double(out, "ang_min_deg", mrpt::RAD2DEG(ang_min));
    LOADABLEOPTS_DUMP_VAR(d_min, double);
    LOADABLEOPTS_DUMP_VAR(sigma0_xx, double);
    LOADABLEOPTS_DUMP_VAR(sigma0_yy, double);
    LOADABLEOPTS_DUMP_VAR(sigma0_zz, double);
    LOADABLEOPTS_DUMP_VAR(p_new_mahalanobis2, double);
    LOADABLEOPTS_DUMP_VAR(candidate_miss_decrement, int);
    LOADABLEOPTS_DUMP_VAR(max_candidate_measurements, int);
    LOADABLEOPTS_DUMP_VAR(refine_initialization, bool);
    dumpVar_string(out, "max_cross_point_range", optionalText(max_cross_point_range, 1));
    dumpVar_string(out, "min_cross_point_range", optionalText(min_cross_point_range, 1));
    LOADABLEOPTS_DUMP_VAR(hit_increment, int);
}

void CCeilingLightsMap::TLikelihoodOptions::loadFromConfigFile(
    const mrpt::config::CConfigFileBase& cfg, const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(p_in, double, cfg, section);
    MRPT_LOAD_CONFIG_VAR(use_type_ii_landmarks, bool, cfg, section);
    requireKey(p_in >= 0 && p_in < 1, section, "p_in", "must be in [0, 1)");
}

void CCeilingLightsMap::TLikelihoodOptions::dumpToTextStream(std::ostream& out) const
{
    out << "\n----------- [CCeilingLightsMap::TLikelihoodOptions] ------------ \n\n";
    LOADABLEOPTS_DUMP_VAR(p_in, double);
    LOADABLEOPTS_DUMP_VAR(use_type_ii_landmarks, bool);
}

void CCeilingLightsMap::TRenderOptions::loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                                           const std::string& section)
{
    MRPT_LOAD_CONFIG_VAR(draw_candidates, bool, cfg, section);
    MRPT_LOAD_CONFIG_VAR(ellipsoid_quantiles, double, cfg, section);
    requireKey(ellipsoid_quantiles > 0, section, "ellipsoid_quantiles", "must be > 0");
}

void CCeilingLightsMap::TRenderOptions::dumpToTextStream(std::ostream& out) const
{
    out << "\n----------- [CCeilingLightsMap::TRenderOptions] ------------ \n\n";
    LOADABLEOPTS_DUMP_VAR(draw_candidates, bool);
    LOADABLEOPTS_DUMP_VAR(ellipsoid_quantiles, double);
}

}  // namespace mrpt_vslam::omni_fastslam
