// kinematica page: a reachability map's voxels, drawn as squares coloured by the
// reachability index (viridis), all of them or one slice. The map is numbers only
// (kinematica.viz.page_reach): flat voxel indices in C order over (nx, ny, nz) and the
// orientations each reaches.
"use strict";

const KM_REACH = (function () {
  // viridis at 0, 0.25, 0.5, 0.75, 1 (matplotlib's), interpolated linearly between
  const VIRIDIS = [[68, 1, 84], [59, 82, 139], [33, 145, 140], [94, 201, 98], [253, 231, 37]];

  function colour(t) {
    const x = Math.max(0, Math.min(1, t)) * (VIRIDIS.length - 1);
    const i = Math.min(VIRIDIS.length - 2, Math.floor(x)), f = x - i;
    const c = [0, 1, 2].map(function (k) {
      return Math.round(VIRIDIS[i][k] + f * (VIRIDIS[i + 1][k] - VIRIDIS[i][k]));
    });
    return "rgb(" + c.join(",") + ")";
  }

  function create(data) {
    if (!data) return null;
    const nx = data.shape[0], ny = data.shape[1], nz = data.shape[2], h = data.resolution;
    const n = data.voxels.length;
    const ijk = new Int32Array(3 * n), centres = new Float64Array(3 * n), colours = new Array(n);
    for (let a = 0; a < n; a++) {
      const v = data.voxels[a];
      const k = v % nz, j = Math.floor(v / nz) % ny, i = Math.floor(v / (ny * nz));
      ijk[3 * a] = i; ijk[3 * a + 1] = j; ijk[3 * a + 2] = k;
      centres[3 * a] = data.origin[0] + (i + 0.5) * h;
      centres[3 * a + 1] = data.origin[1] + (j + 0.5) * h;
      centres[3 * a + 2] = data.origin[2] + (k + 0.5) * h;
      colours[a] = colour(data.reached[a] / data.count);
    }
    const map = {
      data: data,
      size: [nx, ny, nz],
      drawn: 0,
      // The squares of the voxels shown (axis: -1 for all, else 0-2 and the layer along
      // it), each at its centre's depth, into items.
      items: function (items, project, zoom, dpr, axis, layer) {
        const side = Math.max(2 * dpr, 0.8 * h * zoom), alpha = axis < 0 ? 0.35 : 0.85;
        let drawn = 0;
        for (let a = 0; a < n; a++) {
          if (axis >= 0 && ijk[3 * a + axis] !== layer) continue;
          const p = project([centres[3 * a], centres[3 * a + 1], centres[3 * a + 2]]);
          items.push({ z: p.z, kind: "voxel", a: p, size: side, color: colours[a], alpha: alpha });
          drawn++;
        }
        map.drawn = drawn;
      },
      // The coordinate (m) of a layer's centres along an axis.
      at: function (axis, layer) { return data.origin[axis] + (layer + 0.5) * h; },
    };
    return map;
  }

  // The map's panel: shown, its legend drawn, its switch and slice control bound to
  // redraw (which draws the arm and the map again).
  function controls(map, redraw) {
    if (!map) return;
    const $ = function (id) { return document.getElementById(id); };
    $("reach").hidden = false;
    const legend = $("reach-legend"), lc = legend.getContext("2d");
    for (let x = 0; x < legend.width; x++) {
      lc.fillStyle = colour(x / (legend.width - 1));
      lc.fillRect(x, 0, 1, legend.height);
    }
    const d = map.data, asked = d.positions ? "the position alone" : d.count + " orientations";
    const m4 = function (v) { return String(Number(v.toFixed(4))); };
    const about = d.voxels.length + " reachable voxels (" + d.dexterous + " dexterous) of " +
      m4(d.resolution) + " m, " + asked + " each; colour: the share reached, 0 to 1";
    const axis = $("reach-axis"), layer = $("reach-layer");
    const info = function () {
      const a = Number(axis.value);
      $("reach-info").textContent = a < 0 ? about :
        "slice " + "xyz"[a] + " = " + m4(map.at(a, Number(layer.value))) + " m: " + map.drawn +
        " voxels; " + about;
    };
    axis.addEventListener("change", function () {
      const a = Number(axis.value);
      layer.disabled = a < 0;
      if (a >= 0) {
        layer.max = String(map.size[a] - 1);
        layer.value = String(Math.floor(map.size[a] / 2));
      }
      redraw();
      info();
    });
    layer.addEventListener("input", function () { redraw(); info(); });
    $("reach-show").addEventListener("change", function () { redraw(); info(); });
    info();
  }

  return { create: create, colour: colour, controls: controls };
})();
