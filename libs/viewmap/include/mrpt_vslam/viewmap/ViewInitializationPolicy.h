#pragma once

#include <mrpt/config/CLoadableOptions.h>
#include <mrpt_vslam/viewmap/FeatureExistenceModel.h>
#include <mrpt_vslam/viewmap/ViewFeatures.h>
#include <mrpt_vslam/viewmap/ViewMapEKF.h>

#include <Eigen/Core>
#include <deque>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace mrpt::random {
class CRandomGenerator;
}

namespace mrpt_vslam::viewmap {

/** What a view-initialization policy sees at the end of a step (after the EKF updates). */
struct TViewPolicyInputs {
    const ViewMapEKF* ekf = nullptr;
    const TViewFeatures* features = nullptr;  ///< this step's feature points
    std::vector<bool> consistent;             ///< per point: inlier of an accepted observation
    /// One accepted observation of this step.
    struct TObserved {
        size_t view = 0;
        Eigen::Matrix2d R = Eigen::Matrix2d::Identity();  ///< its noise
        size_t inliers = 0;
    };
    std::vector<TObserved> observed;
    /// [m] estimated distance from the robot to the nearest view (+∞ without views).
    double nearest_view_distance = std::numeric_limits<double>::infinity();
    /// P_vv before this step's prediction, after it, and now (after the updates).
    Eigen::Matrix3d P_vv_previous = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d P_vv_predicted = Eigen::Matrix3d::Zero();
};

/** A policy's answer, with the figures it used (written to the run's step table). */
struct TViewDecision {
    enum class TReason {
        None,                ///< no new view
        FirstView,           ///< the map is empty
        NoObservation,       ///< no view could be observed
        FewInliers,          ///< traditional: best inlier count < N_min
        TooFar,              ///< traditional: farther than D_max from every view
        InformationDeficit,  ///< information: the views no longer make up for the motion
        LowExistence,        ///< information: the existence model predicts too few matches
    };
    bool add = false;
    TReason reason = TReason::None;
    double sure_points = std::numeric_limits<double>::quiet_NaN();  ///< n⁻ of the GP
    /// [nats] predicted information balance of the next frame, gain from the observed views
    /// minus loss by motion: ½ log det P_vv now − ½ log det P̂⁺ next frame.
    double information_balance = std::numeric_limits<double>::quiet_NaN();

    static const char* reasonName(TReason r);
};

/** When to start a new view (the subject of Valiente et al. 2015). Two policies, chosen by the ini
 *  key `policy` of TOptions:
 *   - TraditionalViewPolicy: inlier count and distance thresholds (doc/view-slam.md §4.2);
 *   - InformationViewPolicy: the paper's information-based initialization with a Gaussian
 *     process over feature existence (abstract; our criterion, doc/view-slam.md §4.2).
 *  Both keep a minimum spacing between views: no view closer than min_view_spacing to
 *  another, which also keeps φ observable (doc/view-slam.md §4, step 3). */
class ViewInitializationPolicy {
  public:
    enum class TKind { Traditional, Information };

    /// Parameters of both policies (one ini section; every key documented in the configs).
    struct TOptions : public mrpt::config::CLoadableOptions {
        TKind policy = TKind::Information;  ///< ini `policy = traditional | information`
        double min_view_spacing = 0.4;      ///< [m] both
        int min_inliers = 30;               ///< traditional: N_min (> the observation's 20 inliers)
        double max_view_distance = 1.5;     ///< [m] traditional: D_max
        double information_deficit = 0.04;  ///< [nats] information: τ, a frame's deficit
        int deficit_frames = 3;             ///< information: K consecutive deficits
        double min_sure_points = 20;        ///< information: n_min of the predicted n⁻
        int trend_frames = 3;               ///< information: frames the trend of n⁻ spans
        FeatureExistenceModel::TOptions existence;  ///< information: the GP (same section)

        /// Throws std::invalid_argument naming the key of a bad value.
        void validate() const;
        void loadFromConfigFile(const mrpt::config::CConfigFileBase& cfg,
                                const std::string& section) override;
        void saveToConfigFile(mrpt::config::CConfigFileBase& cfg,
                              const std::string& section) const override;
    };

    virtual ~ViewInitializationPolicy() = default;
    /// The policy selected by `options.policy`. \throw std::invalid_argument for bad options.
    static std::unique_ptr<ViewInitializationPolicy> create(const TOptions& options);

    /// Whether to start a view at the current robot pose.
    virtual TViewDecision decide(const TViewPolicyInputs& in,
                                 mrpt::random::CRandomGenerator& rng) = 0;

  protected:
    explicit ViewInitializationPolicy(const TOptions& options) : m_options(options) {}
    /** The rules shared by both policies: the first view, and no view within
     *  min_view_spacing of another (returns a decision), else nullopt. */
    std::optional<TViewDecision> commonRules(const TViewPolicyInputs& in) const;

    TOptions m_options;
};

/** doc/view-slam.md §4.2, traditional: a new view when the best observation has fewer than N_min
 *  inliers (none: no observation) or the robot is farther than D_max from every view. */
class TraditionalViewPolicy : public ViewInitializationPolicy {
  public:
    explicit TraditionalViewPolicy(const TOptions& options) : ViewInitializationPolicy(options) {}
    TViewDecision decide(const TViewPolicyInputs& in, mrpt::random::CRandomGenerator& rng) override;
};

/** Information-based view initialization (Valiente et al. 2015; the criterion is ours,
 *  doc/view-slam.md §4.2). Each step:
 *   1. the GP existence model (FeatureExistenceModel) of the current points gives n⁻_t, the
 *      number of points that surely exist in the map's views; its trend, the mean decline per
 *      frame over the last k = trend_frames frames since the last view, predicts the next
 *      frame's n⁻_{t+1} = n⁻_t − max(0, (n⁻_{t−k} − n⁻_t) / k);
 *   2. the observation noise of a least-squares fit scales as 1/(number of points), so the best
 *      view observed now would next frame give R̂ = R_t · n⁻_t / n⁻_{t+1};
 *   3. information lost by motion: the next prediction is taken to add what the last one did,
 *      P̂⁻ = P_vv + (P_vv⁻ − P_vv,t−1); information gained: the hypothetical EKF update of
 *      P̂⁻ with all the observed views at once, each with its R̂, gives P̂⁺;
 *   4. the balance, gain minus loss, is ½ log det P_vv − ½ log det P̂⁺ (doc/view-slam.md
 *      §4.2, step 4); a view is started after K = deficit_frames consecutive frames whose balance
 *      is below −τ: the views in reach no longer make up for the motion, so the robot's
 *      uncertainty would grow without bound; also when n⁻_{t+1} < n_min (the views are about
 *      to be lost) or nothing is observed.
 */
class InformationViewPolicy : public ViewInitializationPolicy {
  public:
    explicit InformationViewPolicy(const TOptions& options);
    TViewDecision decide(const TViewPolicyInputs& in, mrpt::random::CRandomGenerator& rng) override;

  private:
    void restart();  ///< a view was started: the trend and the deficits begin anew
    FeatureExistenceModel m_existence;
    std::deque<double> m_recent_sure_points;  ///< n⁻ of the frames since the last view
    int m_deficits = 0;                       ///< consecutive frames with a balance below −τ
};

}  // namespace mrpt_vslam::viewmap
