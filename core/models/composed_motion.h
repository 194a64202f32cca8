// The controls between two scans, composed once for a whole particle set instead of once per particle.
//
// Every motion model here is SE(2)-equivariant: a control moves any start pose x by the same displacement in
// x's frame, its Jacobian d x'/d x is [I, S (t' - t); 0, 1] (S the 90-degree turn, t the position), and its
// noise is a covariance in the start frame turned by the heading (twist_motion.h). Then the chain of EKF
// predictions x_k = g(x_{k-1}, u_k), P_k = G_k P_{k-1} G_k^T + Q_k from any start (x_0, P_0) is
//   x_k = x_0 (+) D,   P_k = A P_0 A^T + R Sigma R^T,   A = [I, S (t_k - t_0); 0, 1],   R = rot(theta_0),
// where (D, Sigma) is the same chain run once from the origin with zero covariance: the G_k are R's
// conjugates of the chain's own, and the Q_k its rotations. Victoria Park reads the odometer 61,660 times
// between 6,969 scans; with 100 particles this replaces six million predictions by 61,660.
#ifndef ARBOR_CORE_MODELS_COMPOSED_MOTION_H_
#define ARBOR_CORE_MODELS_COMPOSED_MOTION_H_

#include "core/math/pose2.h"
#include "core/models/motion_model.h"

namespace arbor {

class ComposedMotion {
 public:
  // Appends one control, whose noise in its start frame is `noise` (MotionModel::body_noise).
  void add(const MotionModel& model, const Vec3& u, const BodyProcessNoise& noise) {
    model.predict(&delta_, &covariance_, u, noise);
    ++controls_;
  }
  bool empty() const { return controls_ == 0; }
  void clear() { *this = ComposedMotion{}; }

  // (x, P) carried through every control added, as the chain of predictions would carry them.
  void apply(Pose2* x, Mat3* P) const {
    if (empty()) return;
    const Pose2 end = x->compose(delta_);
    const double c = std::cos(x->theta), s = std::sin(x->theta);
    Mat3 A = Mat3::Identity();
    A(0, 2) = -(end.y - x->y);
    A(1, 2) = end.x - x->x;
    Mat3 R = Mat3::Identity();
    R.topLeftCorner<2, 2>() << c, -s, s, c;
    const Mat3 Q = R * covariance_ * R.transpose();
    *P = A * *P * A.transpose() + 0.5 * (Q + Q.transpose());
    *x = end;
  }

 private:
  Pose2 delta_;                     // the composed displacement, in the start pose's frame
  Mat3 covariance_ = Mat3::Zero();  // the covariance it adds to an exact start, in the same frame
  int controls_ = 0;
};

}  // namespace arbor

#endif  // ARBOR_CORE_MODELS_COMPOSED_MOTION_H_
