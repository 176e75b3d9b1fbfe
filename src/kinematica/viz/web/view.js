// kinematica page: sliders, the 3-D drawing on a canvas, the #q= start, and (when
// served by `kinematica view --serve`) a draggable target solved by robot.ik.
"use strict";

(function () {
  const ROBOT = JSON.parse(document.getElementById("robot-data").textContent);
  const n = ROBOT.joints.length;
  const DEG = Math.PI / 180;
  const COLORS = ["#d62728", "#2ca02c", "#1f77b4"];
  const angleFactor = ROBOT.units.angle === "rad" ? 1 : DEG; // slider unit -> rad
  const lengthFactor = ROBOT.units.length === "mm" ? 0.001 : 1; // slider unit -> m
  const isP = ROBOT.joints.map(function (j) { return j.type === "P"; });
  const factor = isP.map(function (p) { return p ? lengthFactor : angleFactor; });
  const unitName = isP.map(function (p) { return p ? ROBOT.units.length : ROBOT.units.angle; });

  const state = {
    q: ROBOT.q0.slice(),
    target: null, // 16 numbers when serving
    solutions: [],
    branches: [],
    index: 0,
    cam: null,
  };

  const $ = function (id) { return document.getElementById(id); };
  const canvas = $("view");
  const MAP = KM_REACH.create(ROBOT.reach); // null without a map
  const ctx = canvas.getContext("2d");

  // ------------------------------------------------------------------ sliders
  function sliderRange(i) {
    const lim = ROBOT.joints[i].qlim;
    if (lim) return [lim[0] / factor[i], lim[1] / factor[i]];
    if (isP[i]) return [-ROBOT.scale / factor[i], ROBOT.scale / factor[i]];
    return [-Math.PI / factor[i], Math.PI / factor[i]];
  }

  function buildSliders() {
    const box = $("joints");
    for (let i = 0; i < n; i++) {
      const r = sliderRange(i);
      const row = document.createElement("div");
      row.className = "joint";
      const name = ROBOT.joints[i].name ? " " + ROBOT.joints[i].name : "";
      // Names come from the robot file: text nodes and properties, never markup.
      const label = document.createElement("label");
      label.htmlFor = "q" + (i + 1);
      label.textContent = "q" + (i + 1) + name + " (" + unitName[i] + ")";
      const slider = document.createElement("input");
      slider.type = "range";
      slider.id = "q" + (i + 1);
      slider.min = String(r[0]);
      slider.max = String(r[1]);
      slider.step = "any";
      const number = document.createElement("input");
      number.type = "number";
      number.id = "q" + (i + 1) + "-value";
      number.step = "any";
      row.append(label, slider, number);
      box.appendChild(row);
      slider.addEventListener("input", function () { setJoint(i, Number(slider.value), slider); });
      number.addEventListener("change", function () {
        const v = Number(number.value);
        if (Number.isFinite(v)) setJoint(i, v, number);
      });
    }
  }

  function setJoint(i, value, source) {
    state.q[i] = value * factor[i];
    syncInputs(source);
    update(true);
  }

  function syncInputs(source) {
    for (let i = 0; i < n; i++) {
      const slider = $("q" + (i + 1)), number = $("q" + (i + 1) + "-value");
      const v = state.q[i] / factor[i];
      if (slider !== source) slider.value = String(v);
      if (number !== source) number.value = String(Number(v.toFixed(4)));
    }
  }

  // -------------------------------------------------------------------- #q=
  function hashQ() {
    const m = /(?:^|[#&])q=([^&]*)/.exec(window.location.hash);
    if (!m) return null;
    const parts = decodeURIComponent(m[1]).split(",");
    const values = parts.map(function (s) { return s.trim() === "" ? NaN : Number(s); });
    if (values.length !== n || !values.every(Number.isFinite)) {
      showMessage("#q= needs " + n + " numbers (degrees, metres for prismatic joints), got '" +
        decodeURIComponent(m[1]) + "'");
      return null;
    }
    return values.map(function (v, i) { return isP[i] ? v : v * DEG; });
  }

  function writeHash() {
    const text = state.q.map(function (v, i) {
      return String(Number((isP[i] ? v : v / DEG).toFixed(6)));
    }).join(",");
    history.replaceState(null, "", "#q=" + text);
  }

  function showMessage(text) {
    $("message").textContent = text;
  }

  // ----------------------------------------------------------------- numbers
  function fmt(v, digits) {
    const s = (Math.abs(v) < 0.5 * Math.pow(10, -digits) ? 0 : v).toFixed(digits);
    return s;
  }

  function showNumbers(fk) {
    const T = fk.tool;
    const rows = [];
    for (let i = 0; i < 4; i++) {
      rows.push([0, 1, 2, 3].map(function (j) { return fmt(T[4 * i + j], 7).padStart(11); }).join(" "));
    }
    $("T").textContent = rows.join("\n");
    const seq = $("euler").value;
    const e = KM.euler(T, seq);
    const deg = ROBOT.units.angle !== "rad";
    const ang = e.map(function (v) { return fmt(deg ? v / DEG : v, 4); });
    $("pose").textContent =
      "x, y, z (m): " + [3, 7, 11].map(function (k) { return fmt(T[k], 6); }).join(", ") +
      "\nEuler " + seq + " (" + (deg ? "deg" : "rad") + "): " + ang.join(", ");
    const out = [];
    for (let i = 0; i < n; i++) {
      const lim = ROBOT.joints[i].qlim;
      if (lim && (state.q[i] < lim[0] - 1e-12 || state.q[i] > lim[1] + 1e-12)) {
        out.push("q" + (i + 1) + " is outside its limits [" + fmt(lim[0] / factor[i], 4) + ", " +
          fmt(lim[1] / factor[i], 4) + "] " + unitName[i]);
      }
    }
    $("limits").textContent = out.join("; ");
  }

  // ------------------------------------------------------------------ camera
  function resetCamera() {
    const plane = ROBOT.plane;
    let az = -60 * DEG, el = 30 * DEG;
    if (plane && plane[0] === 0 && plane[1] === 1) { az = -90 * DEG; el = 90 * DEG; }
    else if (plane && plane[0] === 0 && plane[1] === 2) { az = -90 * DEG; el = 0; }
    else if (plane) { az = 0; el = 0; }
    state.cam = { az: az, el: el, zoom: null, center: ROBOT.center.slice() };
  }

  function basis() {
    const c = state.cam, ca = Math.cos(c.az), sa = Math.sin(c.az);
    const ce = Math.cos(c.el), se = Math.sin(c.el);
    return {
      right: [-sa, ca, 0],
      up: [-se * ca, -se * sa, ce],
      toward: [ce * ca, ce * sa, se],
    };
  }

  function project(p, B) {
    const c = state.cam, d = [p[0] - c.center[0], p[1] - c.center[1], p[2] - c.center[2]];
    const dot = function (u) { return u[0] * d[0] + u[1] * d[1] + u[2] * d[2]; };
    return {
      x: canvas.width / 2 + c.zoom * dot(B.right),
      y: canvas.height / 2 - c.zoom * dot(B.up),
      z: dot(B.toward),
    };
  }

  // ----------------------------------------------------------------- drawing
  function origin(F) { return [F[3], F[7], F[11]]; }
  function axis(F, j) { return [F[j], F[4 + j], F[8 + j]]; }
  function along(p, u, s) { return [p[0] + s * u[0], p[1] + s * u[1], p[2] + s * u[2]]; }

  function frameItems(items, F, len, width, label, B) {
    const o = origin(F);
    const po = project(o, B);
    for (let j = 0; j < 3; j++) {
      const tip = project(along(o, axis(F, j), len), B);
      items.push({ z: (po.z + tip.z) / 2, kind: "arrow", a: po, b: tip, color: COLORS[j], width: width });
    }
    if (label && $("labels").checked) items.push({ z: po.z + 1e-3, kind: "text", a: po, text: label });
  }

  function draw(fk) {
    const dpr = window.devicePixelRatio || 1;
    const w = Math.max(200, canvas.clientWidth), h = Math.max(200, canvas.clientHeight);
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr);
      canvas.height = Math.round(h * dpr);
    }
    if (state.cam.zoom === null) state.cam.zoom = 0.5 * Math.min(canvas.width, canvas.height) / ROBOT.radius;
    const B = basis();
    const s = ROBOT.scale;
    const items = [];
    // ground grid in the world x-y plane, through the base
    const g = ROBOT.radius, step = ROBOT.grid, cx = ROBOT.center[0], cy = ROBOT.center[1];
    const z0 = ROBOT.base[2][3];
    for (let v = -g; v <= g + 1e-9; v += step) {
      items.push({ z: -1e9, kind: "line", a: project([cx + v, cy - g, z0], B), b: project([cx + v, cy + g, z0], B), color: "#e4e4e4", width: 1 });
      items.push({ z: -1e9, kind: "line", a: project([cx - g, cy + v, z0], B), b: project([cx + g, cy + v, z0], B), color: "#e4e4e4", width: 1 });
    }
    // base plate under S0
    const b0 = origin(KM.flat(ROBOT.base)), pl = 0.08 * s;
    const plate = [[-pl, -pl], [pl, -pl], [pl, pl], [-pl, pl]].map(function (c) {
      return project([b0[0] + c[0], b0[1] + c[1], b0[2]], B);
    });
    items.push({ z: -1e8, kind: "poly", pts: plate, color: "#b0b0b0" });
    // links: through S0..S(n-1) and the tool, as the Python drawing
    const pts = fk.frames.slice(0, n).map(origin).concat([origin(fk.tool)]);
    const P = pts.map(function (p) { return project(p, B); });
    for (let i = 0; i + 1 < P.length; i++) {
      items.push({ z: (P[i].z + P[i + 1].z) / 2, kind: "line", a: P[i], b: P[i + 1], color: "#333333", width: 5 * dpr });
    }
    if (ROBOT.has_tool) {
      const sn = project(origin(fk.frames[n]), B), tp = project(origin(fk.tool), B);
      items.push({ z: (sn.z + tp.z) / 2, kind: "dash", a: sn, b: tp, color: "#333333", width: 1.5 * dpr });
    }
    // joints: cylinders (revolute) and boxes (prismatic) along the joint axis
    const r = 0.025 * s;
    for (let i = 0; i < n; i++) {
      const F = ROBOT.convention === "standard" ? fk.frames[i] : fk.frames[i + 1];
      const o = origin(F), z = axis(F, 2), half = isP[i] ? 2 * r : 1.25 * r;
      const a = project(along(o, z, -half), B), b = project(along(o, z, half), B);
      items.push({ z: (a.z + b.z) / 2 + 1e-4, kind: "joint", a: a, b: b, prismatic: isP[i], width: 2 * r * state.cam.zoom });
    }
    if (MAP && $("reach-show").checked) {
      const axis = Number($("reach-axis").value), layer = Number($("reach-layer").value);
      MAP.items(items, function (p) { return project(p, B); }, state.cam.zoom, dpr, axis, layer);
    } else if (MAP) {
      MAP.drawn = 0;
    }
    if ($("frames").checked) {
      const len = 0.12 * s;
      const groups = {};
      fk.frames.forEach(function (F, i) {
        const key = origin(F).map(function (v) { return v.toFixed(6); }).join(",");
        groups[key] = groups[key] ? groups[key] + ", S" + i : "S" + i;
      });
      const seen = {};
      fk.frames.forEach(function (F) {
        const key = origin(F).map(function (v) { return v.toFixed(6); }).join(",");
        frameItems(items, F, len, 1.5 * dpr, seen[key] ? null : groups[key], B);
        seen[key] = true;
      });
      if (ROBOT.has_tool) frameItems(items, fk.tool, len, 3 * dpr, "tool", B);
      if (ROBOT.has_base) {
        const apart = Math.hypot(b0[0], b0[1], b0[2]) > 1e-9;
        frameItems(items, KM.eye(), len, 1 * dpr, apart ? "W" : null, B);
      }
    }
    if (state.target) {
      frameItems(items, state.target, 0.09 * s, 2.5 * dpr, null, B);
      const tp = project(origin(state.target), B);
      items.push({ z: 1e9, kind: "target", a: tp });
    }
    items.sort(function (u, v) { return u.z - v.z; });
    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.clearRect(0, 0, canvas.width, canvas.height);
    placeLabels(items, dpr);
    items.forEach(function (it) { paint(it, dpr); });
  }

  // Frames close together on the screen ("S4, S5" and "S6" at a wrist) would print
  // their labels over each other: each label moves down a line until it is clear.
  function placeLabels(items, dpr) {
    ctx.font = 12 * dpr + "px sans-serif";
    const placed = [], line = 14 * dpr;
    items.forEach(function (it) {
      if (it.kind !== "text") return;
      const w = ctx.measureText(it.text).width, x = it.a.x + 6 * dpr;
      let y = it.a.y + 14 * dpr;
      const hits = function (b) { return x < b.x + b.w && b.x < x + w && y - line < b.y && b.y - line < y; };
      while (placed.some(hits)) y += line;
      placed.push({ x: x, y: y, w: w });
      it.at = { x: x, y: y };
    });
  }

  function paint(it, dpr) {
    ctx.lineCap = "round";
    ctx.setLineDash([]);
    if (it.kind === "line" || it.kind === "dash") {
      if (it.kind === "dash") ctx.setLineDash([6 * dpr, 4 * dpr]);
      ctx.strokeStyle = it.color; ctx.lineWidth = it.width;
      ctx.beginPath(); ctx.moveTo(it.a.x, it.a.y); ctx.lineTo(it.b.x, it.b.y); ctx.stroke();
    } else if (it.kind === "poly") {
      ctx.fillStyle = it.color; ctx.beginPath();
      it.pts.forEach(function (p, k) { if (k) ctx.lineTo(p.x, p.y); else ctx.moveTo(p.x, p.y); });
      ctx.closePath(); ctx.fill();
    } else if (it.kind === "joint") {
      ctx.lineCap = it.prismatic ? "square" : "round";
      ctx.strokeStyle = "#222222"; ctx.lineWidth = it.width + 2 * dpr;
      ctx.beginPath(); ctx.moveTo(it.a.x, it.a.y); ctx.lineTo(it.b.x + 0.01, it.b.y); ctx.stroke();
      ctx.strokeStyle = it.prismatic ? "#4a90d9" : "#f0a030"; ctx.lineWidth = it.width;
      ctx.beginPath(); ctx.moveTo(it.a.x, it.a.y); ctx.lineTo(it.b.x + 0.01, it.b.y); ctx.stroke();
    } else if (it.kind === "arrow") {
      const dx = it.b.x - it.a.x, dy = it.b.y - it.a.y, L = Math.hypot(dx, dy);
      ctx.strokeStyle = it.color; ctx.fillStyle = it.color; ctx.lineWidth = it.width;
      if (L < 4 * dpr) { // pointing at (or away from) the viewer
        ctx.beginPath(); ctx.arc(it.a.x, it.a.y, 5 * dpr, 0, 2 * Math.PI); ctx.stroke();
        return;
      }
      const ux = dx / L, uy = dy / L, hl = Math.min(10 * dpr, 0.35 * L);
      ctx.beginPath(); ctx.moveTo(it.a.x, it.a.y); ctx.lineTo(it.b.x - ux * hl * 0.8, it.b.y - uy * hl * 0.8); ctx.stroke();
      ctx.beginPath(); ctx.moveTo(it.b.x, it.b.y);
      ctx.lineTo(it.b.x - ux * hl - uy * hl * 0.4, it.b.y - uy * hl + ux * hl * 0.4);
      ctx.lineTo(it.b.x - ux * hl + uy * hl * 0.4, it.b.y - uy * hl - ux * hl * 0.4);
      ctx.closePath(); ctx.fill();
    } else if (it.kind === "text") {
      ctx.fillStyle = "#111111"; ctx.font = 12 * dpr + "px sans-serif";
      ctx.fillText(it.text, it.at.x, it.at.y);
    } else if (it.kind === "voxel") {
      ctx.globalAlpha = it.alpha; ctx.fillStyle = it.color;
      ctx.fillRect(it.a.x - it.size / 2, it.a.y - it.size / 2, it.size, it.size);
      ctx.globalAlpha = 1;
    } else if (it.kind === "target") {
      ctx.strokeStyle = "#e377c2"; ctx.lineWidth = 3 * dpr;
      ctx.beginPath(); ctx.arc(it.a.x, it.a.y, 9 * dpr, 0, 2 * Math.PI); ctx.stroke();
    }
  }

  function update(writeToHash) {
    const fk = KM.frames(ROBOT, state.q);
    showNumbers(fk);
    draw(fk);
    if (writeToHash) writeHash();
    state.fk = fk;
  }

  // ------------------------------------------------------------- mouse/touch
  function bindPointer() {
    let drag = null;
    canvas.addEventListener("pointerdown", function (ev) {
      const dpr = window.devicePixelRatio || 1;
      const rect = canvas.getBoundingClientRect();
      const x = (ev.clientX - rect.left) * dpr, y = (ev.clientY - rect.top) * dpr;
      let mode = ev.shiftKey || ev.button === 2 ? "pan" : "orbit";
      if (state.target) {
        const t = project(origin(state.target), basis());
        if (Math.hypot(t.x - x, t.y - y) < 14 * dpr) mode = "target";
      }
      drag = { mode: mode, x: ev.clientX, y: ev.clientY };
      canvas.setPointerCapture(ev.pointerId);
      ev.preventDefault();
    });
    canvas.addEventListener("pointermove", function (ev) {
      if (!drag) return;
      const dpr = window.devicePixelRatio || 1;
      const dx = ev.clientX - drag.x, dy = ev.clientY - drag.y;
      drag.x = ev.clientX; drag.y = ev.clientY;
      const c = state.cam, B = basis();
      if (drag.mode === "orbit") {
        c.az -= dx * 0.01;
        c.el = Math.max(-Math.PI / 2, Math.min(Math.PI / 2, c.el + dy * 0.01));
      } else {
        const k = dpr / c.zoom, move = [0, 1, 2].map(function (i) { return k * (dx * B.right[i] - dy * B.up[i]); });
        if (drag.mode === "pan") {
          for (let i = 0; i < 3; i++) c.center[i] -= move[i];
        } else {
          for (let i = 0; i < 3; i++) state.target[4 * i + 3] += move[i];
        }
      }
      draw(state.fk);
    });
    const end = function () {
      if (drag && drag.mode === "target") solveTarget();
      drag = null;
    };
    canvas.addEventListener("pointerup", end);
    canvas.addEventListener("pointercancel", end);
    canvas.addEventListener("contextmenu", function (ev) { ev.preventDefault(); });
    canvas.addEventListener("wheel", function (ev) {
      state.cam.zoom *= Math.exp(-ev.deltaY * 0.001);
      draw(state.fk);
      ev.preventDefault();
    }, { passive: false });
  }

  // -------------------------------------------------------------- IK target
  function solveTarget() {
    $("ik-status").textContent = "solving...";
    const T = [0, 1, 2, 3].map(function (i) { return state.target.slice(4 * i, 4 * i + 4); });
    const headers = { "Content-Type": "application/json", "X-Kinematica-Token": ROBOT.token };
    return fetch("api/ik", { method: "POST", headers: headers, body: JSON.stringify({ T: T }) })
      .then(function (r) { return r.json(); })
      .then(function (res) {
        if (res.error) throw new Error(res.error);
        state.solutions = res.solutions || [];
        state.branches = res.branches || [];
        state.index = 0;
        $("ik-status").textContent = res.status + (res.message ? ": " + res.message : "");
        showSolution();
        return res;
      })
      .catch(function (err) {
        $("ik-status").textContent = "IK request failed: " + (err.message || err);
      });
  }

  function showSolution() {
    const k = state.solutions.length;
    $("prev").disabled = $("next").disabled = k < 2;
    if (!k) { $("solution").textContent = "no solution"; update(false); return; }
    const i = ((state.index % k) + k) % k;
    state.index = i;
    state.q = state.solutions[i].slice();
    $("solution").textContent = "solution " + (i + 1) + " of " + k + (state.branches[i] ? ": " + state.branches[i] : "");
    syncInputs(null);
    update(true);
  }

  function targetAtTool() {
    state.target = state.fk.tool.slice();
    state.solutions = [];
    $("solution").textContent = "drag the pink circle, then step through the solutions";
    draw(state.fk);
  }

  // ------------------------------------------------------------------- start
  buildSliders();
  resetCamera();
  const start = hashQ();
  if (start) state.q = start;
  syncInputs(null);
  update(false);
  $("frames").addEventListener("change", function () { draw(state.fk); });
  $("labels").addEventListener("change", function () { draw(state.fk); });
  $("euler").value = ROBOT.euler;
  $("euler").addEventListener("change", function () { showNumbers(state.fk); });
  $("reset-view").addEventListener("click", function () { resetCamera(); draw(state.fk); });
  $("home").addEventListener("click", function () { state.q = ROBOT.q0.slice(); syncInputs(null); update(true); });
  window.addEventListener("hashchange", function () {
    const q = hashQ();
    if (q) { state.q = q; syncInputs(null); update(false); }
  });
  window.addEventListener("resize", function () { draw(state.fk); });
  bindPointer();
  KM_REACH.controls(MAP, function () { draw(state.fk); });
  if (ROBOT.serve) {
    $("serve").hidden = false;
    targetAtTool();
    $("target-reset").addEventListener("click", targetAtTool);
    $("solve").addEventListener("click", solveTarget);
    $("prev").addEventListener("click", function () { state.index -= 1; showSolution(); });
    $("next").addEventListener("click", function () { state.index += 1; showSolution(); });
  }

  // For scripts and tests: read and set the state from the console.
  window.kinematica = {
    q: function () { return state.q.slice(); },
    setQ: function (q) { state.q = q.slice(); syncInputs(null); update(true); },
    T: function () { return state.fk.tool.slice(); },
    target: function () { return state.target ? state.target.slice() : null; },
    setTarget: function (T) { state.target = KM.flat(T); draw(state.fk); return solveTarget(); },
    targetScreen: function () {
      const dpr = window.devicePixelRatio || 1, rect = canvas.getBoundingClientRect();
      const p = project(origin(state.target), basis());
      return [rect.left + p.x / dpr, rect.top + p.y / dpr];
    },
    solutions: function () { return state.solutions.map(function (s) { return s.slice(); }); },
    euler: KM.euler,
    // the map: voxels drawn in the last frame, and a slice (axis -1: none)
    mapDrawn: function () { return MAP ? MAP.drawn : null; },
    setSlice: function (axis, layer) {
      $("reach-axis").value = String(axis);
      $("reach-axis").dispatchEvent(new Event("change"));
      if (axis >= 0) {
        $("reach-layer").value = String(layer);
        $("reach-layer").dispatchEvent(new Event("input"));
      }
    },
    ready: true,
  };
})();
