#include <mrpt/obs/CObservationVisualLandmarks.h>
#include <mrpt/opengl/CEllipsoid3D.h>
#include <mrpt/opengl/CPointCloudColoured.h>
#include <mrpt/opengl/CSetOfObjects.h>
#include <mrpt_vslam/core/AtomicFile.h>
#include <mrpt_vslam/core/HungarianAssignment.h>
#include <mrpt_vslam/core/LandmarkFile.h>
#include <mrpt_vslam/multirobot/CVisualLandmarksMap.h>
#include <mrpt_vslam/multirobot/Cholesky3.h>

#include <Eigen/Core>
#include <algorithm>
#include <bitset>
#include <cmath>
#include <limits>
#include <sstream>
#include <tuple>

using mrpt_vslam::multirobot::CVisualLandmarksMap;

MAP_DEFINITION_REGISTER("mrpt_vslam::multirobot::CVisualLandmarksMap,visualLandmarksMap",
                        mrpt_vslam::multirobot::CVisualLandmarksMap)

IMPLEMENTS_SERIALIZABLE(CVisualLandmarksMap, mrpt::maps::CMetricMap, mrpt_vslam::multirobot)

namespace mrpt_vslam::multirobot {

CVisualLandmarksMap::TMapDefinition::TMapDefinition() = default;

void CVisualLandmarksMap::TMapDefinition::loadFromConfigFile_map_specific(
    const mrpt::config::CConfigFileBase& source, const std::string& sectionNamePrefix)
{
    insertionOpts.loadFromConfigFile(source, sectionNamePrefix + "_insertOpts");
    renderOpts.loadFromConfigFile(source, sectionNamePrefix + "_renderOpts");
}

void CVisualLandmarksMap::TMapDefinition::dumpToTextStream_map_specific(std::ostream& out) const
{
    insertionOpts.dumpToTextStream(out);
    renderOpts.dumpToTextStream(out);
}

mrpt::maps::CMetricMap* CVisualLandmarksMap::internal_CreateFromMapDefinition(
    const mrpt::maps::TMetricMapInitializer& def)
{
    const auto& d = dynamic_cast<const CVisualLandmarksMap::TMapDefinition&>(def);
    auto* map = new CVisualLandmarksMap(
        std::make_shared<LandmarkDescriptorPool>(d.insertionOpts.grid_cell_size));
    map->insertionOptions = d.insertionOpts;
    map->renderOptions = d.renderOpts;
    return map;
}

CVisualLandmarksMap::CVisualLandmarksMap()
    : m_pool(std::make_shared<LandmarkDescriptorPool>(insertionOptions.grid_cell_size))
{
}

CVisualLandmarksMap::CVisualLandmarksMap(std::shared_ptr<LandmarkDescriptorPool> pool)
    : m_pool(std::move(pool))
{
    if (!m_pool) throw std::invalid_argument("CVisualLandmarksMap: null descriptor pool");
}

uint32_t CVisualLandmarksMap::addLandmark(const TVisualLandmark& landmark,
                                          const LandmarkDescriptorPool::TDescriptor& descriptor)
{
    const uint32_t id = m_pool->add(descriptor, landmark.mean);
    m_store.insert(id, landmark);
    return id;
}

TMeasurementCandidates CVisualLandmarksMap::findCandidates(const TLandmarkMeasurement& m,
                                                           const TMapMeasurement& in_map,
                                                           double extra_radius) const
{
    TMeasurementCandidates c;
    m_pool->findCandidates(in_map.z, insertionOptions.search_radius + extra_radius, m.d,
                           insertionOptions.E0, c.candidates);
    return c;
}

namespace {
/// The factor of the innovation covariance Z of landmark `id` (Eq. 6-8).
Cholesky3 innovationFactor(const Eigen::Matrix3d& Z, uint32_t id)
{
    const Cholesky3 L(Z);
    if (!L.ok)
        throw std::invalid_argument("landmark " + std::to_string(id) +
                                    ": innovation covariance not positive definite");
    return L;
}
}  // namespace

CVisualLandmarksMap::TAssociation CVisualLandmarksMap::evaluate(const TMapMeasurement& m,
                                                                uint32_t id) const
{
    const TVisualLandmark* lm = m_store.find(id);
    if (!lm) throw std::invalid_argument("landmark " + std::to_string(id) + " is not in the map");
    const Cholesky3 L = innovationFactor(lm->cov + m.R, id);
    const double D = L.whiten(m.z - lm->mean).squaredNorm();  // Eq. 15
    return TAssociation{id, D, L.logGaussian(D)};             // Eq. 13
}

namespace {
/// associate()'s first requests for one candidate list: the table entries of its first
/// 2·ahead candidates (kPrefetchEntries) or the landmarks of its first `ahead`
/// (kPrefetchLandmarks); inlined, so that each caller holds the requests
[[gnu::always_inline]] inline void prefetchFirstCandidates(
    const LandmarkStore& store, const std::vector<TLandmarkCandidate>& cs,
    CVisualLandmarksMap::TPrefetchStage stage, size_t ahead)
{
    if (stage == CVisualLandmarksMap::kPrefetchEntries)
        for (size_t i = 0; i < std::min(2 * ahead, cs.size()); i++) store.prefetchEntry(cs[i].id);
    else
        for (size_t i = 0; i < std::min(ahead, cs.size()); i++) store.prefetchLandmark(cs[i].id);
}
}  // namespace

std::optional<CVisualLandmarksMap::TAssociation> CVisualLandmarksMap::associate(
    const TMapMeasurement& m, const TMeasurementCandidates& candidates,
    const std::vector<uint32_t>* excluded, int64_t identity) const
{
    if (insertionOptions.associate_by_identity && identity >= 0) {  // known correspondences
        const auto id = m_pool->landmarkOfIdentity(identity);
        if (!id || !m_store.find(*id)) return std::nullopt;
        return evaluate(m, *id);
    }
    // Alg. 1 lines 19-29: the smallest E among the landmarks with D ≤ D0. The candidates
    // (E ≤ E0 already) come in increasing E, so the first one inside the gate is it; among
    // equal E (no descriptors, as in range-bearing data: all E = 0) the smallest D.
    // D = vᵀ Z⁻¹ v ≥ |v|² / tr(Z): a candidate that bound puts outside the gate, or behind the
    // best so far, is passed over before its factorization; log N only for the chosen one.
    constexpr double kRounding = 1 + 1e-9;
    struct TBest {
        uint32_t id;
        double D;
        float E;
        Cholesky3 L;  ///< of Z
    };
    std::optional<TBest> best;
    const auto& cs = candidates.candidates;
    constexpr size_t kAhead = kPrefetchAhead;
    prefetchFirstCandidates(m_store, cs, kPrefetchEntries, kAhead);
    prefetchFirstCandidates(m_store, cs, kPrefetchLandmarks, kAhead);
    for (size_t i = 0; i < cs.size(); i++) {
        const auto& c = cs[i];
        if (best && c.E > best->E) break;
        if (i + 2 * kAhead < cs.size()) m_store.prefetchEntry(cs[i + 2 * kAhead].id);
        if (i + kAhead < cs.size()) m_store.prefetchLandmark(cs[i + kAhead].id);
        const TVisualLandmark* lm = m_store.find(c.id);
        if (!lm ||
            (excluded && std::find(excluded->begin(), excluded->end(), c.id) != excluded->end()))
            continue;
        const Eigen::Matrix3d Z = lm->cov + m.R;
        const Eigen::Vector3d v = m.z - lm->mean;
        const double limit = best ? std::min(best->D, insertionOptions.D0) : insertionOptions.D0;
        if (v.squaredNorm() > kRounding * limit * Z.trace()) continue;
        const Cholesky3 L = innovationFactor(Z, c.id);
        const double D = L.whiten(v).squaredNorm();                           // Eq. 15
        if (!(D <= insertionOptions.D0) || (best && D >= best->D)) continue;  // line 28
        best = TBest{c.id, D, c.E, L};
    }
    if (!best) return std::nullopt;
    return TAssociation{best->id, best->D, best->L.logGaussian(best->D)};  // Eq. 13
}

void CVisualLandmarksMap::prefetchAssociation(const std::vector<TMeasurementCandidates>& candidates,
                                              TPrefetchStage stage) const
{
    if (stage == kPrefetchTable) {
        m_store.prefetchTable();
        return;
    }
    for (const auto& c : candidates)
        prefetchFirstCandidates(m_store, c.candidates, stage, kPrefetchAhead);
}

std::vector<std::optional<CVisualLandmarksMap::TAssociation>> CVisualLandmarksMap::associateJointly(
    const std::vector<TMapMeasurement>& m,
    const std::vector<TMeasurementCandidates>& candidates) const
{
    if (m.size() != candidates.size())
        throw std::invalid_argument("associateJointly(): one candidate list per point needed");
    // columns: the candidates of any point that this map holds
    std::vector<uint32_t> ids;
    for (const auto& c : candidates)
        for (const auto& l : c.candidates)
            if (m_store.find(l.id)) ids.push_back(l.id);
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());

    constexpr double kForbidden = std::numeric_limits<double>::infinity();
    Eigen::MatrixXd cost = Eigen::MatrixXd::Constant(
        static_cast<Eigen::Index>(m.size()), static_cast<Eigen::Index>(ids.size()), kForbidden);
    std::vector<std::vector<TAssociation>> pairs(m.size());
    for (size_t j = 0; j < m.size(); j++)
        for (const auto& l : candidates[j].candidates) {
            if (!m_store.find(l.id)) continue;
            const TAssociation a = evaluate(m[j], l.id);
            if (!(a.D <= insertionOptions.D0)) continue;  // the gate of Alg. 1 line 27
            const auto col = std::lower_bound(ids.begin(), ids.end(), l.id) - ids.begin();
            cost(static_cast<Eigen::Index>(j), col) = -a.log_likelihood;
            pairs[j].push_back(a);
        }
    const auto assignment = core::solveHungarianAssignment(cost, -std::log(insertionOptions.p0));
    std::vector<std::optional<TAssociation>> out(m.size());
    for (size_t j = 0; j < m.size(); j++) {
        const int col = assignment.row_to_col[j];
        if (col < 0) continue;
        for (const auto& a : pairs[j])
            if (a.id == ids[static_cast<size_t>(col)]) out[j] = a;
    }
    return out;
}

std::vector<std::optional<CVisualLandmarksMap::TAssociation>>
CVisualLandmarksMap::associateNearestFirst(
    const std::vector<TLandmarkMeasurement>& z, const std::vector<TMapMeasurement>& in_map,
    const std::vector<TMeasurementCandidates>& candidates) const
{
    if (z.size() != in_map.size() || z.size() != candidates.size())
        throw std::invalid_argument("associateNearestFirst(): one point and candidate list each");
    std::vector<std::optional<TAssociation>> out(z.size());
    std::vector<bool> decided(z.size(), false);
    std::vector<uint32_t> taken;
    struct TPair {
        float E;
        TAssociation a;
        size_t point;
    };
    std::vector<TPair> pairs;
    for (size_t j = 0; j < z.size(); j++) {
        if (insertionOptions.associate_by_identity && z[j].identity >= 0) {
            out[j] = associate(in_map[j], candidates[j], nullptr, z[j].identity);
            decided[j] = true;
            if (out[j]) taken.push_back(out[j]->id);
            continue;
        }
        for (const auto& c : candidates[j].candidates) {
            if (!m_store.find(c.id)) continue;
            const TAssociation a = evaluate(in_map[j], c.id);
            if (a.D <= insertionOptions.D0) pairs.push_back({c.E, a, j});  // Alg. 1 line 27
        }
    }
    std::sort(pairs.begin(), pairs.end(), [](const TPair& x, const TPair& y) {
        return std::tie(x.E, x.a.D, x.point, x.a.id) < std::tie(y.E, y.a.D, y.point, y.a.id);
    });
    for (const TPair& p : pairs) {
        if (decided[p.point] || std::find(taken.begin(), taken.end(), p.a.id) != taken.end())
            continue;
        out[p.point] = p.a;
        decided[p.point] = true;
        taken.push_back(p.a.id);
    }
    return out;
}

TFusionResult CVisualLandmarksMap::fuse(const TLandmarkMeasurement& m,
                                        const TMapMeasurement& in_map,
                                        TMeasurementCandidates& candidates, unsigned robot)
{
    return fuseAs(m, in_map, candidates, robot, associate(in_map, candidates, nullptr, m.identity));
}

uint32_t CVisualLandmarksMap::reserveNewId(const TLandmarkMeasurement& m,
                                           const TMapMeasurement& in_map,
                                           TMeasurementCandidates& candidates)
{
    if (candidates.new_id) return *candidates.new_id;
    const bool known = insertionOptions.associate_by_identity && m.identity >= 0;
    if (known) candidates.new_id = m_pool->landmarkOfIdentity(m.identity);
    if (!candidates.new_id) candidates.new_id = m_pool->add(m.d, in_map.z);
    if (known) m_pool->setLandmarkOfIdentity(m.identity, *candidates.new_id);
    return *candidates.new_id;
}

TFusionResult CVisualLandmarksMap::fuseAs(const TLandmarkMeasurement& m,
                                          const TMapMeasurement& in_map,
                                          TMeasurementCandidates& candidates, unsigned robot,
                                          const std::optional<TAssociation>& a)
{
    TFusionResult r;
    if (!a) {  // Alg. 1 lines 33-36
        const uint32_t id = reserveNewId(m, in_map, candidates);
        TVisualLandmark lm;
        lm.mean = in_map.z;
        lm.cov = in_map.R;
        lm.times_seen = 1;
        lm.seen_by = 1u << robot;
        m_store.insert(id, lm);
        r.id = id;
        r.created = true;
        r.log_w = std::log(insertionOptions.p0);
        return r;
    }
    TVisualLandmark& lm = m_store.modify(a->id);                                // lines 39-42
    const Eigen::Matrix3d K = lm.cov * Cholesky3(lm.cov + in_map.R).inverse();  // Σ Z⁻¹
    lm.mean += K * (in_map.z - lm.mean);
    const Eigen::Matrix3d cov = lm.cov - K * lm.cov;
    lm.cov = 0.5 * (cov + cov.transpose());
    lm.times_seen++;
    lm.seen_by |= 1u << robot;
    r.id = a->id;
    r.log_w = a->log_likelihood;  // Eq. 13
    return r;
}

std::vector<TFusionResult> CVisualLandmarksMap::fuseFrame(
    const std::vector<TLandmarkMeasurement>& z, const std::vector<TMapMeasurement>& in_map,
    std::vector<TMeasurementCandidates>& candidates, unsigned robot, TFrameAssociation rule,
    bool create)
{
    std::vector<TFusionResult> results(z.size());
    const auto fuseOne = [&](size_t j, const std::optional<TAssociation>& a) {
        if (a || create) return fuseAs(z[j], in_map[j], candidates[j], robot, a);
        TFusionResult r;  // line 36, the landmark left to the caller
        r.created = true;
        r.log_w = std::log(insertionOptions.p0);
        return r;
    };
    if (insertionOptions.joint_association || rule == TFrameAssociation::DistinctNearestFirst) {
        const auto assoc = insertionOptions.joint_association
                               ? associateJointly(in_map, candidates)
                               : associateNearestFirst(z, in_map, candidates);
        for (size_t j = 0; j < z.size(); j++) results[j] = fuseOne(j, assoc[j]);
        return results;
    }
    const bool distinct = rule == TFrameAssociation::DistinctInOrder;
    std::vector<uint32_t> taken;
    for (size_t j = 0; j < z.size(); j++) {
        const auto a =
            associate(in_map[j], candidates[j], distinct ? &taken : nullptr, z[j].identity);
        if (a && distinct) taken.push_back(a->id);
        results[j] = fuseOne(j, a);
    }
    return results;
}

size_t CVisualLandmarksMap::removeLandmarksSeenLessThan(unsigned min_times_seen)
{
    std::vector<uint32_t> rare;
    m_store.forEach([&](uint32_t id, const TVisualLandmark& lm) {
        if (lm.times_seen < min_times_seen) rare.push_back(id);
    });
    for (const uint32_t id : rare) m_store.erase(id);
    return rare.size();
}

bool CVisualLandmarksMap::isEmpty() const { return m_store.empty(); }

void CVisualLandmarksMap::internal_clear() { m_store.clear(); }

bool CVisualLandmarksMap::internal_insertObservation(
    const mrpt::obs::CObservation& obs, const std::optional<const mrpt::poses::CPose3D>& robotPose)
{
    const auto* o = dynamic_cast<const mrpt::obs::CObservationVisualLandmarks*>(&obs);
    if (!o) return false;
    const mrpt::math::TPose2D robot =
        robotPose ? mrpt::math::TPose2D(robotPose->x(), robotPose->y(), robotPose->yaw())
                  : mrpt::math::TPose2D(0, 0, 0);
    for (const auto& m : measurementsFromObservation(*o)) {
        const TMapMeasurement in_map = toMapFrame(m, robot);
        auto candidates = findCandidates(m, in_map);
        fuse(m, in_map, candidates, 0);
    }
    return true;
}

bool CVisualLandmarksMap::internal_canComputeObservationLikelihood(
    const mrpt::obs::CObservation& obs) const
{
    return dynamic_cast<const mrpt::obs::CObservationVisualLandmarks*>(&obs) != nullptr;
}

double CVisualLandmarksMap::internal_computeObservationLikelihood(
    const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const
{
    const auto* o = dynamic_cast<const mrpt::obs::CObservationVisualLandmarks*>(&obs);
    if (!o) return 0;
    const mrpt::math::TPose2D robot(takenFrom.x(), takenFrom.y(), takenFrom.yaw());
    double log_lik = 0;
    for (const auto& m : measurementsFromObservation(*o)) {
        const TMapMeasurement in_map = toMapFrame(m, robot);
        const auto a = associate(in_map, findCandidates(m, in_map), nullptr, m.identity);
        log_lik += a ? a->log_likelihood : std::log(insertionOptions.p0);
    }
    return log_lik;
}

float CVisualLandmarksMap::compute3DMatchingRatio(const mrpt::maps::CMetricMap*,
                                                  const mrpt::poses::CPose3D&,
                                                  const mrpt::maps::TMatchingRatioParams&) const
{
    return 0;  // not defined for sparse landmark maps
}

void CVisualLandmarksMap::saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const
{
    core::LandmarkFile file;
    core::AtomicFile descriptor_file(filNamePrefix + "_descriptors.txt");
    std::ostream& descriptors = descriptor_file.stream();
    descriptors << "# visual landmarks (CVisualLandmarksMap): id times_seen seen_by_robot_mask "
                   "and the 64 U-SURF values\n";
    m_store.forEach([&](uint32_t id, const TVisualLandmark& lm) {
        core::TLandmark out;
        out.id = static_cast<int>(id);
        out.position = {lm.mean.x(), lm.mean.y(), lm.mean.z()};
        out.cov = lm.cov;
        out.has_cov = true;
        file.landmarks.push_back(out);
        descriptors << id << ' ' << lm.times_seen << ' ' << lm.seen_by;
        for (const float v : m_pool->descriptor(id)) descriptors << ' ' << v;
        descriptors << '\n';
    });
    file.save(filNamePrefix + ".txt", "multi-robot visual landmarks map (CVisualLandmarksMap)");
    descriptor_file.commit();
}

void CVisualLandmarksMap::getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const
{
    if (!genericMapParams.enableSaveAs3DObject) return;
    // colour: landmarks one robot saw in blue, landmarks several robots merged in red
    const auto colourOf = [](const TVisualLandmark& lm) {
        return std::bitset<32>(lm.seen_by).count() > 1 ? mrpt::img::TColorf(0.9f, 0.1f, 0.1f)
                                                       : mrpt::img::TColorf(0.1f, 0.3f, 1.0f);
    };
    auto cloud = mrpt::opengl::CPointCloudColoured::Create();
    cloud->setPointSize(renderOptions.point_size);
    m_store.forEach([&](uint32_t id, const TVisualLandmark& lm) {
        const auto c = colourOf(lm);
        cloud->push_back(static_cast<float>(lm.mean.x()), static_cast<float>(lm.mean.y()),
                         static_cast<float>(lm.mean.z()), c.R, c.G, c.B);
        if (!renderOptions.draw_ellipsoids) return;
        auto ellipsoid = mrpt::opengl::CEllipsoid3D::Create();
        ellipsoid->setCovMatrixAndMean(mrpt::math::CMatrixDouble33(lm.cov),
                                       mrpt::math::CMatrixFixed<double, 3, 1>(lm.mean));
        ellipsoid->setQuantiles(static_cast<float>(renderOptions.ellipsoid_quantiles));
        ellipsoid->setColor(c.R, c.G, c.B, 0.4f);
        ellipsoid->setName(mrpt::format("landmark_%u", id));
        o.insert(ellipsoid);
    });
    o.insert(cloud);
}

std::string CVisualLandmarksMap::asString() const
{
    size_t merged = 0;
    m_store.forEach([&](uint32_t, const TVisualLandmark& lm) {
        merged += std::bitset<32>(lm.seen_by).count() > 1 ? 1 : 0;
    });
    std::ostringstream s;
    s << "CVisualLandmarksMap: " << m_store.size() << " landmarks (" << merged
      << " measured by several robots)";
    return s.str();
}

}  // namespace mrpt_vslam::multirobot
