// kinematica page: forward kinematics and Euler angles, in plain JavaScript.
// The page computes FK itself from the DH table embedded in it (no server, no
// network); tests hold it equal to kinematica's robot.fk to 1e-6.
// Matrices are flat arrays of 16 numbers, row by row.
"use strict";

const KM = {};

KM.eye = function () {
  return [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1];
};

KM.mul = function (A, B) {
  const C = new Array(16);
  for (let i = 0; i < 4; i++) {
    for (let j = 0; j < 4; j++) {
      let s = 0;
      for (let k = 0; k < 4; k++) s += A[4 * i + k] * B[4 * k + j];
      C[4 * i + j] = s;
    }
  }
  return C;
};

KM.flat = function (M) {
  return [].concat(M[0], M[1], M[2], M[3]);
};

// One DH link matrix. standard (Paul): Rot(z,θ)·Tras(z,d)·Tras(x,a)·Rot(x,α);
// modified (Craig): Rot(x,α)·Tras(x,a)·Rot(z,θ)·Tras(z,d), a and α being a(i-1), α(i-1).
KM.link = function (theta, d, a, alpha, convention) {
  const ct = Math.cos(theta), st = Math.sin(theta);
  const ca = Math.cos(alpha), sa = Math.sin(alpha);
  if (convention === "modified") {
    return [ct, -st, 0, a, st * ca, ct * ca, -sa, -sa * d, st * sa, ct * sa, ca, ca * d, 0, 0, 0, 1];
  }
  return [ct, -st * ca, st * sa, a * ct, st, ct * ca, -ct * sa, a * st, 0, sa, ca, d, 0, 0, 0, 1];
};

// Every frame at q (rad, m): S0 = base, S1..Sn (DH frames), and the tool pose.
KM.frames = function (robot, q) {
  const out = [KM.flat(robot.base)];
  robot.joints.forEach(function (j, i) {
    const theta = j.theta + (j.type === "R" ? q[i] : 0);
    const d = j.d + (j.type === "P" ? q[i] : 0);
    out.push(KM.mul(out[i], KM.link(theta, d, j.a, j.alpha, robot.convention)));
  });
  return { frames: out, tool: KM.mul(out[out.length - 1], KM.flat(robot.tool)) };
};

KM.wrap = function (a) {
  // to (-π, π], as kinematica.wrap_angle
  const twoPi = 2 * Math.PI;
  return Math.PI - (((Math.PI - a) % twoPi) + twoPi) % twoPi + 0;
};

// Unit quaternion (x, y, z, w) of the rotation part of T (Shepperd's method).
KM.quat = function (T) {
  const R = function (i, j) { return T[4 * i + j]; };
  const diag = [R(0, 0), R(1, 1), R(2, 2)];
  const tr = diag[0] + diag[1] + diag[2];
  let q;
  let best = 3, bestVal = tr;
  for (let i = 0; i < 3; i++) if (diag[i] > bestVal) { best = i; bestVal = diag[i]; }
  if (best === 3) {
    q = [R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1), 1 + tr];
  } else {
    const i = best, j = (i + 1) % 3, k = (i + 2) % 3;
    q = [0, 0, 0, 0];
    q[i] = 1 - tr + 2 * R(i, i);
    q[j] = R(j, i) + R(i, j);
    q[k] = R(k, i) + R(i, k);
    q[3] = R(k, j) - R(j, k);
  }
  const n = Math.hypot(q[0], q[1], q[2], q[3]);
  return q.map(function (v) { return v / n; });
};

KM.GIMBAL_LOCK_TOL = 1e-7;

// Euler angles (rad) of T's rotation in sequence seq, as kinematica.euler_from_matrix:
// the direct method of Bernardes & Viollet (2022); upper case intrinsic, lower
// case extrinsic; in gimbal lock the third angle is 0.
KM.euler = function (T, seq) {
  const extrinsic = seq === seq.toLowerCase();
  const idx = { x: 0, y: 1, z: 2 };
  let axes = seq.toLowerCase().split("").map(function (c) { return idx[c]; });
  if (!extrinsic) axes = axes.slice().reverse();
  let i = axes[0], j = axes[1], k = axes[2];
  const symmetric = i === k;
  if (symmetric) k = 3 - i - j;
  const sign = ((i - j) * (j - k) * (k - i)) / 2;
  const q = KM.quat(T);
  const w = q[3], qi = q[i], qj = q[j], qk = sign * q[k];
  let a, b, c, d;
  if (symmetric) { a = w; b = qi; c = qj; d = qk; }
  else { a = w - qj; b = qi + qk; c = qj + w; d = qk - qi; }
  const middle = 2 * Math.atan2(Math.hypot(c, d), Math.hypot(a, b));
  const halfSum = Math.atan2(b, a), halfDiff = Math.atan2(d, c);
  const thirdSign = symmetric ? 1 : sign;
  const nearZero = middle <= KM.GIMBAL_LOCK_TOL;
  const nearPi = middle >= Math.PI - KM.GIMBAL_LOCK_TOL;
  let first, third;
  if (nearZero || nearPi) {
    first = nearZero ? 2 * halfSum : (extrinsic ? -2 : 2) * halfDiff;
    if (!extrinsic) first = thirdSign * first;
    third = 0;
  } else {
    const extFirst = halfSum - halfDiff;
    const extThird = thirdSign * (halfSum + halfDiff);
    first = extrinsic ? extFirst : extThird;
    third = extrinsic ? extThird : extFirst;
  }
  const second = symmetric ? middle : middle - Math.PI / 2;
  return [KM.wrap(first), second, KM.wrap(third)];
};
