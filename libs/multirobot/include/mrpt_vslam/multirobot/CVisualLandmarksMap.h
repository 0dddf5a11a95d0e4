#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt/maps/CMetricMap.h>
#include <mrpt/maps/TMetricMapTypesRegistry.h>
#include <mrpt/math/TPose2D.h>
#include <mrpt_vslam/multirobot/LandmarkDescriptorPool.h>
#include <mrpt_vslam/multirobot/LandmarkMeasurement.h>
#include <mrpt_vslam/multirobot/LandmarkStore.h>

#include <memory>
#include <optional>
#include <vector>

namespace mrpt_vslam::multirobot {

/** What fusing one measurement did to the map (Alg. 1 lines 19-45). */
struct TFusionResult {
    double log_w = 0;      ///< log ω (Eq. 13), or log p0 for a new landmark (line 36)
    uint32_t id = 0;       ///< landmark updated or created
    bool created = false;  ///< a new landmark (line 33)
};

/** The search for one measurement, done once and shared by every particle's map: the
 *  candidates with E ≤ E0 near the measured point, and the id a new landmark gets (handed out
 *  by the pool the first time a particle creates it, so all particles use the same id). */
struct TMeasurementCandidates {
    std::vector<TLandmarkCandidate> candidates;
    std::optional<uint32_t> new_id;
};

/** One particle's map of 3D visual landmarks shared by a robot team (Gil et al., "Estimation
 *  of Visual Maps with a Robot Network Equipped with Vision Sensors", Sensors 2010;
 *  doc/multirobot.md): per landmark the EKF (μ_j, Σ_j) and the U-SURF descriptor d_j (Eq. 5).
 *
 *  Fusing a measurement o = (z, d) taken from a robot pose x (fuse()):
 *   1. z_w = g⁻¹(x, z), R_w: the point and R_t in the map frame (g is a rigid transform, so
 *      its Jacobian G is a rotation and the EKF can run in the map frame exactly);
 *   2. candidates: landmarks with descriptor distance E ≤ E0 (Eq. 16) near z_w (the pool's
 *      spatial index); for each one this map holds, D = vᵀ Z⁻¹ v, Z = Σ_j + R_w (Eq. 8, 15);
 *   3. c = argmin E among those with D ≤ D0 (Alg. 1 lines 27-29); none: a new landmark with
 *      μ = z_w, Σ = R_w (line 34-35; the paper's Gᵀ R_t⁻¹ G is an information matrix, its
 *      inverse G⁻¹ R_t G⁻ᵀ is the covariance meant) and weight p0 (line 36);
 *   4. else the EKF update (Eq. 9-11) and the weight N(v; 0, Z) (Eq. 13).
 *
 *  Storage: landmarks in a copy-on-write LandmarkStore, descriptors in a LandmarkDescriptorPool
 *  that copies of the map share, so particles copied by resampling share what they have not
 *  changed. A map read from a file or created from an .ini gets a pool of its own.
 *
 *  Usage: create it from an `.ini` through `CMultiMetricMap` (`visualLandmarksMap_count = 1`,
 *  see doc/multirobot.md) or directly; insertObservation() of a `CObservationVisualLandmarks`
 *  at a known robot pose fuses all its landmarks; computeObservationLikelihood() gives the
 *  weight a stock MRPT particle filter needs; saveMetricMapRepresentationToFile() writes
 *  `<prefix>.txt` (map.txt format) and `<prefix>_descriptors.txt`. */
class CVisualLandmarksMap : public mrpt::maps::CMetricMap {
    DEFINE_SERIALIZABLE(CVisualLandmarksMap, mrpt_vslam::multirobot)

  public:
    /** Data association and initialization ("<prefix>_insertOpts"). The paper gives no values
     *  for D0, E0 and p0 ("selected experimentally"); ours are in doc/multirobot.md. */
    struct TInsertionOptions : public mrpt::config::CLoadableOptions {
        /// D0: gate on the squared Mahalanobis distance (Alg. 1 line 27); χ²₃(0.99) = 11.34.
        double D0 = 11.34;
        /// E0: largest descriptor distance E of an association (Alg. 1 line 30). U-SURF of a
        /// corner seen from elsewhere is often 0.3-1 away; 0.25 duplicates landmarks.
        double E0 = 0.7;
        /// p0: weight of a measurement that creates a landmark (Alg. 1 line 36) [1/m³].
        double p0 = 0.5;
        /// Candidates are searched within this distance of the measured point [m], on top of
        /// the particles' spread (the filter adds it).
        double search_radius = 1.5;
        /// Edge of the cells of the descriptor pool's spatial hash [m].
        double grid_cell_size = 1.0;
        /// Associate the points of one frame jointly (associateJointly(), ours) instead of
        /// one by one (associate(), the paper's Alg. 1).
        bool joint_association = false;
        /// Known correspondences: a measurement with an identity (TLandmarkMeasurement::
        /// identity ≥ 0) goes to the landmark that identity started, whatever its D, or starts
        /// it; measurements without one go through the gate. Not with joint_association.
        bool associate_by_identity = false;

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    } insertionOptions;

    /** 3D rendering ("<prefix>_renderOpts"). */
    struct TRenderOptions : public mrpt::config::CLoadableOptions {
        bool draw_ellipsoids = true;       ///< covariance ellipsoids (else points only)
        double ellipsoid_quantiles = 3.0;  ///< ellipsoids at this many σ
        float point_size = 4.0f;           ///< [px]

        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void dumpToTextStream(std::ostream& out) const override;
    } renderOptions;

    CVisualLandmarksMap();
    /// A map that shares `pool` with other maps (the particles of one filter).
    explicit CVisualLandmarksMap(std::shared_ptr<LandmarkDescriptorPool> pool);

    /// @name Contents
    /// @{
    const LandmarkStore& landmarks() const { return m_store; }
    size_t size() const { return m_store.size(); }
    const LandmarkDescriptorPool& descriptorPool() const { return *m_pool; }
    std::shared_ptr<LandmarkDescriptorPool> sharedDescriptorPool() const { return m_pool; }
    /// Adds a landmark (e.g. a prior map) and returns its id.
    uint32_t addLandmark(const TVisualLandmark& landmark,
                         const LandmarkDescriptorPool::TDescriptor& descriptor);
    /// @}

    /// @name Data association and update (Alg. 1 lines 19-45)
    /// @{
    /** Step 2's pool search for a measurement in the map frame, with the search radius
     *  insertionOptions.search_radius + `extra_radius` (the particles' spread). */
    TMeasurementCandidates findCandidates(const TLandmarkMeasurement& m,
                                          const TMapMeasurement& in_map,
                                          double extra_radius = 0) const;
    /// An association of step 3: the landmark, its D and log N(v; 0, Z).
    struct TAssociation {
        uint32_t id = 0;
        double D = 0, log_likelihood = 0;
    };
    /** The landmark the measurement is associated with (steps 2-3), or nullopt for "new".
     *  Landmarks listed in `excluded` (e.g. already taken by another point of the same
     *  frame) are passed over. With associate_by_identity and `identity` ≥ 0, the landmark of
     *  that identity instead (ungated), or nullopt if there is none yet. */
    std::optional<TAssociation> associate(const TMapMeasurement& m,
                                          const TMeasurementCandidates& candidates,
                                          const std::vector<uint32_t>* excluded = nullptr,
                                          int64_t identity = -1) const;
    /** The associations of all points of one frame and robot at once (ours, doc/multirobot.md
     *  §3): the assignment of the points to distinct landmarks, or to new ones, of largest
     *  likelihood, N(v; 0, Z) per pair inside the gates (D ≤ D0, E ≤ E0) and p0 per new
     *  landmark (Alg. 1 line 36), by the Hungarian method. Returns one entry per point. */
    std::vector<std::optional<TAssociation>> associateJointly(
        const std::vector<TMapMeasurement>& m,
        const std::vector<TMeasurementCandidates>& candidates) const;
    /** The associations of all points `z` of one frame and robot (`in_map`, `candidates`:
     *  one per point) to distinct landmarks, nearest pair first (global nearest neighbour,
     *  ours): a point with an identity (associate_by_identity) takes its landmark, as
     *  associate(); then, over every other pair inside the gates (D ≤ D0, E ≤ E0), the pair
     *  of smallest E, among equal E of smallest D, is made, its point and landmark leave the
     *  rest, and so on. A point left without a pair gets nullopt (a new landmark). For one
     *  point it is associate(). Returns one entry per point. */
    std::vector<std::optional<TAssociation>> associateNearestFirst(
        const std::vector<TLandmarkMeasurement>& z, const std::vector<TMapMeasurement>& in_map,
        const std::vector<TMeasurementCandidates>& candidates) const;
    /** Starts loading what associate() reads first for these candidate lists, in the stages
     *  that a loop over particles requests some particles apart, each when the previous one's
     *  lines are in the cache: kPrefetchTable (this map's table of blocks), kPrefetchEntries (the
     *  table's entries of the first candidates), kPrefetchLandmarks (those landmarks). Changes
     *  nothing. */
    enum TPrefetchStage { kPrefetchTable, kPrefetchEntries, kPrefetchLandmarks };
    void prefetchAssociation(const std::vector<TMeasurementCandidates>& candidates,
                             TPrefetchStage stage) const;
    /// D and log N(v; 0, Z) of the measurement against landmark `id` of this map, ungated.
    TAssociation evaluate(const TMapMeasurement& m, uint32_t id) const;
    /// The landmark with this id (nullptr if this map does not hold it).
    const TVisualLandmark* landmark(uint32_t id) const { return m_store.find(id); }
    /** Steps 3-4 for one measurement: association, EKF update or creation, weight.
     *  \param robot index of the robot that measured it (seen_by bit, < 32) */
    TFusionResult fuse(const TLandmarkMeasurement& m, const TMapMeasurement& in_map,
                       TMeasurementCandidates& candidates, unsigned robot);
    /** The id a landmark created from `m` gets (Alg. 1 lines 33-36), kept in
     *  candidates.new_id so that every particle creating it uses the same: the one already
     *  there, else the landmark of m's identity (known correspondences), else a new pool id
     *  created at in_map.z. Changes the shared pool: call it from one thread at a time. */
    uint32_t reserveNewId(const TLandmarkMeasurement& m, const TMapMeasurement& in_map,
                          TMeasurementCandidates& candidates);
    /** Step 4 with the association already made (`a`, or nullopt for a new landmark): the
     *  EKF update of landmark a->id, or its creation (reserveNewId()); the result's log_w is
     *  a->log_likelihood or log p0. With candidates.new_id set for every `a` = nullopt,
     *  particles (maps sharing one pool) may call it on parallel threads. */
    TFusionResult fuseAs(const TLandmarkMeasurement& m, const TMapMeasurement& in_map,
                         TMeasurementCandidates& candidates, unsigned robot,
                         const std::optional<TAssociation>& a);
    /// How fuseFrame() associates the points of a frame when joint_association is off.
    enum class TFrameAssociation {
        OneByOne,              ///< fuse() each point in turn
        DistinctInOrder,       ///< in turn, a landmark taken by a point not offered to the next
        DistinctNearestFirst,  ///< associateNearestFirst()
    };
    /** Alg. 1 lines 18-46 for the measurements of one frame of one robot: with
     *  joint_association fuseAs() the associations of associateJointly(), else as `rule`
     *  says. `candidates` (one per measurement) are searched before the frame is fused, so
     *  two points of one frame never become one landmark. Returns one result per measurement.
     *  With `create` false a point left without a landmark changes nothing: its result is
     *  `created` with log p0 and no id, and the caller creates the landmark with fuseAs()
     *  (particles fusing on parallel threads, the pool's ids handed out between). */
    std::vector<TFusionResult> fuseFrame(const std::vector<TLandmarkMeasurement>& z,
                                         const std::vector<TMapMeasurement>& in_map,
                                         std::vector<TMeasurementCandidates>& candidates,
                                         unsigned robot, TFrameAssociation rule,
                                         bool create = true);
    /// Removes the landmarks fused from fewer than `min_times_seen` measurements; returns how
    /// many it removed.
    size_t removeLandmarksSeenLessThan(unsigned min_times_seen);
    /// @}

    /// @name CMetricMap interface
    /// @{
    bool isEmpty() const override;
    /// `<prefix>.txt`: `# id x y z cxx cxy cxz cyy cyz czz`; `<prefix>_descriptors.txt`:
    /// `id times_seen seen_by d1 ... d64`.
    void saveMetricMapRepresentationToFile(const std::string& filNamePrefix) const override;
    void getVisualizationInto(mrpt::opengl::CSetOfObjects& o) const override;
    std::string asString() const override;
    float compute3DMatchingRatio(const mrpt::maps::CMetricMap* otherMap,
                                 const mrpt::poses::CPose3D& otherMapPose,
                                 const mrpt::maps::TMatchingRatioParams& params) const override;
    /// @}

    MAP_DEFINITION_START(CVisualLandmarksMap)
    mrpt_vslam::multirobot::CVisualLandmarksMap::TInsertionOptions insertionOpts;
    mrpt_vslam::multirobot::CVisualLandmarksMap::TRenderOptions renderOpts;
    MAP_DEFINITION_END(CVisualLandmarksMap)

  protected:
    void internal_clear() override;
    bool internal_insertObservation(
        const mrpt::obs::CObservation& obs,
        const std::optional<const mrpt::poses::CPose3D>& robotPose = std::nullopt) override;
    double internal_computeObservationLikelihood(
        const mrpt::obs::CObservation& obs, const mrpt::poses::CPose3D& takenFrom) const override;
    bool internal_canComputeObservationLikelihood(
        const mrpt::obs::CObservation& obs) const override;

  private:
    /// associate() requests a candidate's table entry 2·kPrefetchAhead candidates and its
    /// landmark kPrefetchAhead candidates before it reads them
    static constexpr size_t kPrefetchAhead = 4;
    LandmarkStore m_store;
    std::shared_ptr<LandmarkDescriptorPool> m_pool;
};

}  // namespace mrpt_vslam::multirobot
