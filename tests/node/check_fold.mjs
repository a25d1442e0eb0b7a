// Check a FOLD file with libraries curvefold did not write:
//   node check_fold.mjs FILE
// Prints one JSON object:
//   fold:       the `fold` library rebuilds the faces of the key frame (2D crease pattern) from
//               edges_vertices and vertices_coords; compared with faces_vertices as vertex sets
//               and as counter-clockwise cycles.
//   rabbit_ear: Rabbit Ear's graph validation (duplicate/circular edges, isolated vertices,
//               references), its face winding of the crease pattern, and for every folded frame
//               the crease pattern folded by that frame's edges_foldAngle with Rabbit Ear
//               (one connected sheet at a time), compared with the frame's vertices_coords after
//               the best rigid motion per sheet (Horn's quaternion method): max_distance.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";

const require = createRequire(import.meta.url);
const FOLD = require("fold");
const ear = require("rabbit-ear");

const file = process.argv[2];
if (!file) {
  console.error("usage: node check_fold.mjs FILE");
  process.exit(2);
}
const doc = JSON.parse(readFileSync(file, "utf8"));
const keyFrame = Object.fromEntries(Object.entries(doc).filter(([k]) => !k.startsWith("file_")));

// ---- fold library: rebuild faces from the planar graph --------------------------------
function canonicalCycle(face) {
  let best = null;
  for (let i = 0; i < face.length; i += 1) {
    const rotated = face.slice(i).concat(face.slice(0, i));
    const key = rotated.join(",");
    if (best === null || key < best) best = key;
  }
  return best;
}
const rebuilt = FOLD.convert.edges_vertices_to_faces_vertices_edges({
  vertices_coords: keyFrame.vertices_coords.map((c) => c.slice(0, 2)),
  edges_vertices: keyFrame.edges_vertices.map((e) => e.slice()),
});
const asSet = (faces) => new Set(faces.map((f) => f.slice().sort((a, b) => a - b).join(",")));
const fileSets = asSet(keyFrame.faces_vertices);
const rebuiltSets = asSet(rebuilt.faces_vertices);
const missing = [...fileSets].filter((k) => !rebuiltSets.has(k));
const extra = [...rebuiltSets].filter((k) => !fileSets.has(k));
const fileCycles = new Set(keyFrame.faces_vertices.map(canonicalCycle));
const sameOrientation = rebuilt.faces_vertices.every((f) => fileCycles.has(canonicalCycle(f)));
const foldReport = {
  faces_file: keyFrame.faces_vertices.length,
  faces_rebuilt: rebuilt.faces_vertices.length,
  same_vertex_sets: missing.length === 0 && extra.length === 0,
  same_orientation: missing.length === 0 && extra.length === 0 && sameOrientation,
  missing: missing.slice(0, 10),
  extra: extra.slice(0, 10),
};

// ---- rabbit ear: validation, winding, folding ---------------------------------------
const graph = JSON.parse(JSON.stringify(keyFrame));
const valid = ear.graph.validate(graph);
const winding = ear.graph.makeFacesWinding(graph);

function jacobiLargestEigenvector(a) {
  // Cyclic Jacobi on a symmetric 4x4 matrix; returns the eigenvector of the largest eigenvalue.
  const n = 4;
  const m = a.map((row) => row.slice());
  const v = [...Array(n)].map((_, i) => [...Array(n)].map((__, j) => (i === j ? 1 : 0)));
  for (let sweep = 0; sweep < 100; sweep += 1) {
    let off = 0;
    for (let p = 0; p < n; p += 1) for (let q = p + 1; q < n; q += 1) off += m[p][q] * m[p][q];
    if (off < 1e-30) break;
    for (let p = 0; p < n; p += 1) {
      for (let q = p + 1; q < n; q += 1) {
        if (Math.abs(m[p][q]) < 1e-300) continue;
        const theta = (m[q][q] - m[p][p]) / (2 * m[p][q]);
        const t = Math.sign(theta || 1) / (Math.abs(theta) + Math.sqrt(theta * theta + 1));
        const c = 1 / Math.sqrt(t * t + 1);
        const s = t * c;
        for (let k = 0; k < n; k += 1) {
          const mkp = m[k][p];
          const mkq = m[k][q];
          m[k][p] = c * mkp - s * mkq;
          m[k][q] = s * mkp + c * mkq;
        }
        for (let k = 0; k < n; k += 1) {
          const mpk = m[p][k];
          const mqk = m[q][k];
          m[p][k] = c * mpk - s * mqk;
          m[q][k] = s * mpk + c * mqk;
        }
        for (let k = 0; k < n; k += 1) {
          const vkp = v[k][p];
          const vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
    }
  }
  let best = 0;
  for (let i = 1; i < n; i += 1) if (m[i][i] > m[best][best]) best = i;
  return v.map((row) => row[best]);
}

function rigidResidual(src, dst) {
  // Max distance between dst and the best rotation + translation of src (Horn 1987).
  const count = src.length;
  const mean = (pts) => [0, 1, 2].map((k) => pts.reduce((acc, p) => acc + p[k], 0) / count);
  const ca = mean(src);
  const cb = mean(dst);
  const S = [[0, 0, 0], [0, 0, 0], [0, 0, 0]];
  for (let i = 0; i < count; i += 1) {
    for (let r = 0; r < 3; r += 1) {
      for (let c = 0; c < 3; c += 1) S[r][c] += (src[i][r] - ca[r]) * (dst[i][c] - cb[c]);
    }
  }
  const [[xx, xy, xz], [yx, yy, yz], [zx, zy, zz]] = S;
  const N = [
    [xx + yy + zz, yz - zy, zx - xz, xy - yx],
    [yz - zy, xx - yy - zz, xy + yx, zx + xz],
    [zx - xz, xy + yx, -xx + yy - zz, yz + zy],
    [xy - yx, zx + xz, yz + zy, -xx - yy + zz],
  ];
  const [w, x, y, z] = jacobiLargestEigenvector(N);
  const R = [
    [w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y)],
    [2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x)],
    [2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z],
  ];
  let worst = 0;
  for (let i = 0; i < count; i += 1) {
    const d = [0, 1, 2].map((k) => src[i][k] - ca[k]);
    const moved = [0, 1, 2].map((r) => R[r][0] * d[0] + R[r][1] * d[1] + R[r][2] * d[2] + cb[r]);
    worst = Math.max(worst, Math.hypot(moved[0] - dst[i][0], moved[1] - dst[i][1], moved[2] - dst[i][2]));
  }
  return worst;
}

function faceComponents(faces_faces) {
  const label = new Array(faces_faces.length).fill(-1);
  const roots = [];
  for (let f = 0; f < faces_faces.length; f += 1) {
    if (label[f] !== -1) continue;
    roots.push(f);
    const stack = [f];
    label[f] = roots.length - 1;
    while (stack.length) {
      const g = stack.pop();
      for (const h of faces_faces[g]) {
        if (label[h] === -1) {
          label[h] = roots.length - 1;
          stack.push(h);
        }
      }
    }
  }
  return { label, roots };
}

const faces_faces = ear.graph.makeFacesFaces(graph);
const { label, roots } = faceComponents(faces_faces);
const frames = (doc.file_frames ?? []).map((frame, i) => {
  const merged = frame.frame_inherit ? { ...keyFrame, ...frame } : frame;
  const target = merged.vertices_coords.map((c) => [c[0], c[1], c[2] ?? 0]);
  const base = { ...graph, edges_foldAngle: merged.edges_foldAngle, faces_faces };
  let worst = 0;
  roots.forEach((root, component) => {
    const folded = ear.graph.makeVerticesCoordsFolded(base, root);
    const verts = [...new Set(graph.faces_vertices
      .filter((_, f) => label[f] === component)
      .flat())];
    worst = Math.max(worst, rigidResidual(verts.map((v) => folded[v]), verts.map((v) => target[v])));
  });
  return { title: frame.frame_title ?? `frame ${i + 1}`, max_distance: worst };
});

console.log(JSON.stringify({
  fold: foldReport,
  rabbit_ear: {
    summary: valid.summary,
    duplicate_edges: valid.edges.duplicate.length,
    circular_edges: valid.edges.circular.length,
    isolated_vertices: valid.vertices.isolated.length,
    references_ok: valid.vertices.references && valid.edges.references && valid.faces.references,
    faces_ccw: winding.filter(Boolean).length,
    faces_cw: winding.filter((w) => !w).length,
    sheets: roots.length,
    frames,
  },
}));
