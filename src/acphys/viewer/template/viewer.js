// acphys viewer: a replay of an acphys run, drawn with WebGL2. Everything it shows is in this
// page: the description (#acphys-data) and a gzip'd blob of arrays (#acphys-blob) it refers to.
(function () {
  'use strict';

  const $ = (id) => document.getElementById(id);
  const root = document.documentElement;
  const viewer = {
    ready: false, time: 0, frames: 0, error: null, bodies: [],
    setTime: (t) => setTime(t), play: () => setPlaying(true), pause: () => setPlaying(false),
    select: (name) => select(bodies.findIndex((b) => b.name === name)),
    screenPosition: (name) => screenPosition(bodies.findIndex((b) => b.name === name)),
    project: (x, y, z) => project([x, y, z]),
    colour: (name) => { const b = bodies.find((c) => c.name === name); return b ? b.colour.slice() : null; },
  };
  window.acphysViewer = viewer;

  const BLOCK = 192;
  const PALETTE = [[0.95, 0.45, 0.2], [0.3, 0.65, 1.0], [0.95, 0.85, 0.25], [0.75, 0.4, 0.95],
    [0.35, 0.9, 0.55], [1.0, 0.4, 0.6], [0.3, 0.9, 0.9], [0.85, 0.6, 0.35]];
  const EVENT_COLOURS = { hit_ground: [0.35, 0.89, 0.36], leave_ground: [0.95, 0.64, 0.23],
    collision: [1.0, 0.3, 0.3], collision_end: [1.0, 0.6, 0.7] };
  const OTHER_EVENT = [0.7, 0.61, 1.0];
  const TYPES = { f32: Float32Array, f64: Float64Array, u32: Uint32Array, i32: Int32Array, u8: Uint8Array };

  let data, buffer, gl, bodies = [], events = null, t0 = 0, t1 = 0, time = 0;
  let playing = false, speed = 1, selected = -1, dirty = true, lastClock = 0, shownRecord = '';
  const camera = { target: [96, 96, 50], yaw: -1.9, pitch: 0.75, dist: 60 };
  const ui = {};

  function fail(message) {
    viewer.error = message;
    root.dataset.state = 'error';
    note('cannot show the replay: ' + message);
  }
  function note(text) {
    const div = document.createElement('div');
    div.textContent = text;
    $('notes').appendChild(div);
  }

  // ---- data ------------------------------------------------------------------------------
  async function inflate(text) {
    if (typeof DecompressionStream === 'undefined') {
      throw new Error('this browser has no DecompressionStream (Chrome 80+, Firefox 113+, Safari 16.4+ have)');
    }
    const bin = atob(text.trim());
    const bytes = new Uint8Array(bin.length);
    for (let i = 0; i < bin.length; i++) bytes[i] = bin.charCodeAt(i);
    const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('gzip'));
    return new Response(stream).arrayBuffer();
  }
  const arr = (ref) => new TYPES[ref[0]](buffer, ref[1], ref[2]);

  function eventKind(text) { return text.split(':', 1)[0]; }
  function eventColour(text) { return EVENT_COLOURS[eventKind(text)] || OTHER_EVENT; }

  function prepareBodies() {
    const all = {}, widths = data.records.widths;
    for (const key in data.records.columns) all[key] = arr(data.records.columns[key]);
    bodies = data.bodies.map((b, index) => {
      const c = {};
      for (const key in all) c[key] = all[key].subarray(b.first * widths[key], (b.first + b.records) * widths[key]);
      const shape = data.shapes[b.shape];
      const n = b.records, pos = new Float64Array(3 * n);
      for (let i = 0; i < n; i++) {
        const cell = c.cell[i];
        pos[3 * i] = (((cell >>> 24) & 255) - data.base.x) * BLOCK + c.origin[3 * i];
        pos[3 * i + 1] = (((cell >>> 16) & 255) - data.base.y) * BLOCK + c.origin[3 * i + 1];
        pos[3 * i + 2] = c.origin[3 * i + 2];
      }
      return { name: b.name, id: b.id, n, stride: b.stride, spheres: shape.spheres, cylinders: shape.cylinders,
        shape: shape.source, c, pos, colour: PALETTE[index % PALETTE.length], cursor: 0,
        at: [0, 0, 0], q: [1, 0, 0, 0], visible: false };
    });
    viewer.bodies = bodies.map((b) => b.name);
    const e = data.events;
    events = { body: arr(e.body), t: arr(e.t), position: arr(e.position), text: arr(e.text), strings: e.strings };
    for (const b of bodies) b.events = [];
    for (let k = 0; k < events.t.length; k++) if (events.body[k] < bodies.length) bodies[events.body[k]].events.push(k);
  }

  // The record of body b at time t: the last with t_i <= t (-1 before the first).
  function recordAt(b, t) {
    const ts = b.c.t;
    let i = b.cursor;
    if (i < b.n && ts[i] <= t && (i + 1 >= b.n || ts[i + 1] > t)) return i;
    let lo = 0, hi = b.n - 1;
    if (b.n === 0 || t < ts[0]) return -1;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (ts[mid] <= t) lo = mid; else hi = mid - 1; }
    b.cursor = lo;
    return lo;
  }

  // Where body b is at time t (interpolated between its records), into b.at and b.q.
  function place(b, t) {
    const i = recordAt(b, t);
    b.visible = i >= 0;
    if (i < 0) return i;
    const p = b.pos, q = b.c.orientation, ts = b.c.t;
    let f = 0;
    if (i + 1 < b.n && ts[i + 1] - ts[i] > 0 && ts[i + 1] - ts[i] < 0.5) f = (t - ts[i]) / (ts[i + 1] - ts[i]);
    const j = f > 0 ? i + 1 : i;
    for (let k = 0; k < 3; k++) b.at[k] = p[3 * i + k] + (p[3 * j + k] - p[3 * i + k]) * f;
    let dot = 0;
    for (let k = 0; k < 4; k++) dot += q[4 * i + k] * q[4 * j + k];
    const s = dot < 0 ? -1 : 1;
    let len = 0;
    for (let k = 0; k < 4; k++) { b.q[k] = q[4 * i + k] + (s * q[4 * j + k] - q[4 * i + k]) * f; len += b.q[k] * b.q[k]; }
    len = Math.sqrt(len) || 1;
    for (let k = 0; k < 4; k++) b.q[k] /= len;
    return i;
  }

  // v rotated by the quaternion q = [w, x, y, z], written into out.
  function rotate(q, x, y, z, out) {
    const w = q[0], qx = q[1], qy = q[2], qz = q[3];
    const tx = 2 * (qy * z - qz * y), ty = 2 * (qz * x - qx * z), tz = 2 * (qx * y - qy * x);
    out[0] = x + w * tx + (qy * tz - qz * ty);
    out[1] = y + w * ty + (qz * tx - qx * tz);
    out[2] = z + w * tz + (qx * ty - qy * tx);
  }

  // ---- GL helpers --------------------------------------------------------------------------
  function shader(type, source) {
    const s = gl.createShader(type);
    gl.shaderSource(s, source);
    gl.compileShader(s);
    if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
    return s;
  }
  function program(vs, fs, uniforms) {
    const p = gl.createProgram();
    gl.attachShader(p, shader(gl.VERTEX_SHADER, '#version 300 es\n' + vs));
    gl.attachShader(p, shader(gl.FRAGMENT_SHADER, '#version 300 es\nprecision highp float;\n' + fs));
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(p));
    const u = { program: p };
    for (const name of uniforms) u[name] = gl.getUniformLocation(p, name);
    return u;
  }
  // A vertex array: attribs are [location, size, stride floats, offset floats, divisor] in a buffer.
  function vertexArray(buf, attribs, index, instBuf, instAttribs) {
    const vao = gl.createVertexArray();
    gl.bindVertexArray(vao);
    const bind = (b, list) => {
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      for (const [loc, size, stride, offset, divisor] of list) {
        gl.enableVertexAttribArray(loc);
        gl.vertexAttribPointer(loc, size, gl.FLOAT, false, stride * 4, offset * 4);
        gl.vertexAttribDivisor(loc, divisor || 0);
      }
    };
    bind(buf, attribs);
    if (instBuf) bind(instBuf, instAttribs);
    if (index) gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, index);
    gl.bindVertexArray(null);
    return vao;
  }
  function staticBuffer(values, target) {
    const b = gl.createBuffer();
    gl.bindBuffer(target || gl.ARRAY_BUFFER, b);
    gl.bufferData(target || gl.ARRAY_BUFFER, values, gl.STATIC_DRAW);
    return b;
  }

  const LIT_FS = `in vec3 vNormal; in vec4 vColour; out vec4 outColour; uniform vec3 uLight;
    void main() { float d = abs(dot(normalize(vNormal), uLight));
      outColour = vec4(vColour.rgb * (0.38 + 0.62 * d), vColour.a); }`;
  const MESH_VS = `layout(location=0) in vec3 aPos; layout(location=1) in vec3 aNormal;
    layout(location=2) in vec4 aColour; uniform mat4 uViewProj; out vec3 vNormal; out vec4 vColour;
    void main() { vNormal = aNormal; vColour = aColour; gl_Position = uViewProj * vec4(aPos, 1.0); }`;
  const INST_VS = `layout(location=0) in vec3 aPos; layout(location=1) in vec3 aNormal;
    layout(location=2) in vec4 aInst; layout(location=3) in float aHeight; layout(location=4) in vec4 aColour;
    uniform mat4 uViewProj; uniform float uMinScale; out vec3 vNormal; out vec4 vColour;
    void main() { vNormal = aNormal; vColour = aColour;
      // Never smaller than uMinScale * depth (a few pixels): bodies stay visible from afar.
      float depth = (uViewProj * vec4(aInst.xyz, 1.0)).w;
      float grow = aInst.w > 0.0 ? max(1.0, uMinScale * depth / aInst.w) : 1.0;
      vec3 p = aInst.xyz + vec3(aPos.xy * aInst.w, aPos.z * aHeight) * grow;
      gl_Position = uViewProj * vec4(p, 1.0); }`;
  const LINE_VS = `layout(location=0) in vec3 aPos; layout(location=1) in vec4 aColour; layout(location=2) in float aT;
    uniform mat4 uViewProj; out vec4 vColour; out float vT;
    void main() { vColour = aColour; vT = aT; gl_Position = uViewProj * vec4(aPos, 1.0); }`;
  const LINE_FS = `in vec4 vColour; in float vT; uniform float uTime; out vec4 outColour;
    void main() { if (vT > uTime) discard; outColour = vColour; }`;
  const POINT_VS = `layout(location=0) in vec3 aPos; layout(location=1) in vec4 aColour; layout(location=2) in float aT;
    uniform mat4 uViewProj; uniform float uTime; uniform float uScale; out vec4 vColour; out float vAge;
    void main() { vColour = aColour; vAge = uTime - aT; gl_Position = uViewProj * vec4(aPos, 1.0);
      bool gone = vAge < 0.0 || (vAge > 0.8 && aColour.a < 0.5);
      gl_PointSize = gone ? 0.0 : uScale * mix(22.0, 6.0, clamp(vAge / 0.8, 0.0, 1.0)); }`;
  const POINT_FS = `in vec4 vColour; in float vAge; out vec4 outColour;
    void main() { if (vAge < 0.0 || (vAge > 0.8 && vColour.a < 0.5)) discard;
      float r = length(gl_PointCoord - 0.5) * 2.0; if (r > 1.0) discard;
      float ring = vAge < 0.8 ? smoothstep(0.55, 0.75, r) : 0.85; outColour = vec4(vColour.rgb, ring); }`;

  // Interleaved [x y z nx ny nz r g b a] for triangles (9 floats each), with flat normals.
  function flatMesh(tri, colourOf) {
    const n = tri.length / 9, out = new Float32Array(n * 30);
    for (let i = 0; i < n; i++) {
      const a = 9 * i;
      const ux = tri[a + 3] - tri[a], uy = tri[a + 4] - tri[a + 1], uz = tri[a + 5] - tri[a + 2];
      const vx = tri[a + 6] - tri[a], vy = tri[a + 7] - tri[a + 1], vz = tri[a + 8] - tri[a + 2];
      let nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      const len = Math.hypot(nx, ny, nz) || 1;
      nx /= len; ny /= len; nz /= len;
      for (let k = 0; k < 3; k++) {
        const o = 30 * i + 10 * k, col = colourOf(i, k);
        out.set([tri[a + 3 * k], tri[a + 3 * k + 1], tri[a + 3 * k + 2], nx, ny, nz, col[0], col[1], col[2], col[3]], o);
      }
    }
    return out;
  }
  function meshDraw(values) {
    if (!values.length) return null;
    const buf = staticBuffer(values);
    return { vao: vertexArray(buf, [[0, 3, 10, 0], [1, 3, 10, 3], [2, 4, 10, 6]]), count: values.length / 10 };
  }

  function unitSphere() {
    const pos = [], idx = [], rings = 8, slices = 14;
    for (let i = 0; i <= rings; i++) {
      const th = Math.PI * i / rings;
      for (let j = 0; j <= slices; j++) {
        const ph = 2 * Math.PI * j / slices;
        const x = Math.sin(th) * Math.cos(ph), y = Math.sin(th) * Math.sin(ph), z = Math.cos(th);
        pos.push(x, y, z, x, y, z);
      }
    }
    for (let i = 0; i < rings; i++) for (let j = 0; j < slices; j++) {
      const a = i * (slices + 1) + j, b = a + slices + 1;
      idx.push(a, b, a + 1, a + 1, b, b + 1);
    }
    return { pos: new Float32Array(pos), idx: new Uint16Array(idx) };
  }
  function unitCylinder() {
    const pos = [], idx = [], slices = 20;
    for (let j = 0; j <= slices; j++) {
      const ph = 2 * Math.PI * j / slices, x = Math.cos(ph), y = Math.sin(ph);
      pos.push(x, y, 0, x, y, 0, x, y, 1, x, y, 0);
    }
    for (let j = 0; j < slices; j++) { const a = 2 * j; idx.push(a, a + 2, a + 1, a + 1, a + 2, a + 3); }
    for (const z of [0, 1]) {
      const centre = pos.length / 6;
      pos.push(0, 0, z, 0, 0, 1);
      for (let j = 0; j <= slices; j++) {
        const ph = 2 * Math.PI * j / slices;
        pos.push(Math.cos(ph), Math.sin(ph), z, 0, 0, 1);
      }
      for (let j = 0; j < slices; j++) idx.push(centre, centre + 1 + j, centre + 2 + j);
    }
    return { pos: new Float32Array(pos), idx: new Uint16Array(idx) };
  }
  // Instances [x y z r h r g b a]: a unit mesh drawn at each.
  function instanced(mesh, values, dynamic) {
    const buf = staticBuffer(mesh.pos), index = staticBuffer(mesh.idx, gl.ELEMENT_ARRAY_BUFFER);
    const inst = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, inst);
    gl.bufferData(gl.ARRAY_BUFFER, values, dynamic ? gl.DYNAMIC_DRAW : gl.STATIC_DRAW);
    const vao = vertexArray(buf, [[0, 3, 6, 0], [1, 3, 6, 3]], index, inst,
      [[2, 4, 9, 0, 1], [3, 1, 9, 4, 1], [4, 4, 9, 5, 1]]);
    return { vao, inst, values, count: mesh.idx.length, instances: values.length / 9 };
  }

  // ---- the scene -----------------------------------------------------------------------------
  let progs, draws = {};
  function heightColour(h, lo, hi) {
    const f = hi - lo > 0.5 ? (h - lo) / (hi - lo) : 0.3;
    const stops = [[0.27, 0.45, 0.22], [0.45, 0.55, 0.25], [0.55, 0.45, 0.3], [0.85, 0.85, 0.85]];
    const x = Math.min(0.999, Math.max(0, f)) * (stops.length - 1), i = Math.floor(x), u = x - i;
    return [0, 1, 2].map((k) => stops[i][k] + (stops[i + 1][k] - stops[i][k]) * u).concat([1]);
  }

  function buildScene() {
    const scene = data.scene;
    const grid = [];  // [x y z r g b a t]
    const gridColour = [1, 1, 1, 0.13], never = -1e30;
    if (scene) {
      const blocks = scene.terrain.map((b) => ({ x: b.x, y: b.y, h: arr(b.heights), w: arr(b.water), cut: arr(b.cut) }));
      let lo = Infinity, hi = -Infinity;
      for (const b of blocks) for (const h of b.h) { lo = Math.min(lo, h); hi = Math.max(hi, h); }
      const tri = [], water = [];
      for (const b of blocks) {
        const v = (ix, iy) => [b.x + 24 * ix, b.y + 24 * iy, b.h[9 * ix + iy], b.w[9 * ix + iy]];
        for (let cx = 0; cx < 8; cx++) for (let cy = 0; cy < 8; cy++) {
          const sw = v(cx, cy), se = v(cx + 1, cy), ne = v(cx + 1, cy + 1), nw = v(cx, cy + 1);
          // ConstructPolygons: a SW-NE cut gives (SW, SE, NE), (SW, NE, NW); else (SW, SE, NW), (NE, NW, SE).
          const corners = b.cut[8 * cx + cy] ? [sw, se, ne, sw, ne, nw] : [sw, se, nw, ne, nw, se];
          for (const c of corners) { tri.push(c[0], c[1], c[2]); water.push(c[3]); }
          const z = (p) => p[2] + 0.03;
          grid.push(sw[0], sw[1], z(sw), ...gridColour, never, se[0], se[1], z(se), ...gridColour, never);
          grid.push(sw[0], sw[1], z(sw), ...gridColour, never, nw[0], nw[1], z(nw), ...gridColour, never);
          if (cy === 7) grid.push(nw[0], nw[1], z(nw), ...gridColour, never, ne[0], ne[1], z(ne), ...gridColour, never);
          if (cx === 7) grid.push(se[0], se[1], z(se), ...gridColour, never, ne[0], ne[1], z(ne), ...gridColour, never);
        }
      }
      const waterColour = [0.16, 0.38, 0.85, 1];
      draws.terrain = meshDraw(flatMesh(new Float32Array(tri), (i, k) => water[3 * i + k] ? waterColour
        : heightColour(tri[9 * i + 3 * k + 2], lo, hi)));
      const ownerColour = (owner, alpha) => {
        const g = 0.62 + 0.18 * ((owner * 0.618) % 1);
        return [g, g * 0.97, g * 0.9, alpha];
      };
      const layer = (part, alpha, tint) => {
        const t = arr(part.triangles), owner = arr(part.owner);
        return meshDraw(flatMesh(t, (i) => tint || ownerColour(owner[i], alpha)));
      };
      draws.solids = layer(scene.solids, 1);
      draws.shells = layer(scene.shells, 0.28, [0.85, 0.75, 0.6, 0.28]);
      draws.rooms = layer(scene.rooms, 0.22, [0.55, 0.75, 0.95, 0.22]);
      const prim = (part, five) => {
        const v = arr(part.values), n = v.length / (five ? 5 : 4), out = new Float32Array(9 * n);
        for (let i = 0; i < n; i++) {
          const a = (five ? 5 : 4) * i;
          out.set([v[a], v[a + 1], v[a + 2], v[a + 3], five ? v[a + 4] : v[a + 3], 0.7, 0.66, 0.6, 1], 9 * i);
        }
        return n ? instanced(five ? unitCylinder() : unitSphere(), out, false) : null;
      };
      draws.cylinders = prim(scene.cylinders, true);
      draws.spheres = prim(scene.spheres, false);
    }
    // Trails: a segment per pair of records, coloured by the speed between them, shown once reached.
    let segments = 0;
    for (const b of bodies) segments += Math.max(0, b.n - 1);
    const seg = new Float32Array(segments * 2);
    let s = 0;
    for (const b of bodies) for (let i = 0; i + 1 < b.n; i++) {
      const dt = b.c.t[i + 1] - b.c.t[i], p = b.pos;
      const d = Math.hypot(p[3 * i + 3] - p[3 * i], p[3 * i + 4] - p[3 * i + 1], p[3 * i + 5] - p[3 * i + 2]);
      seg[s++] = dt > 0 ? d / dt : 0;
    }
    const speeds = seg.slice().sort();
    const top = niceCeil(1.15 * Math.max(0.5, speeds.length ? speeds[Math.floor(0.98 * (speeds.length - 1))] : 1));
    $('ramp-max').textContent = '0 to ' + top + ' m/s';
    // Segments in the order they are reached (by the time of their end), so a frame draws the
    // prefix reached by then: one draw call, nothing of the future rasterised.
    const owner = new Uint32Array(segments), start = new Uint32Array(segments), ends = new Float64Array(segments);
    s = 0;
    for (let bi = 0; bi < bodies.length; bi++) for (let i = 0; i + 1 < bodies[bi].n; i++) {
      owner[s] = bi; start[s] = i; ends[s] = bodies[bi].c.t[i + 1]; s++;
    }
    const order = Array.from({ length: segments }, (_, k) => k).sort((a, b) => ends[a] - ends[b] || a - b);
    const trail = new Float32Array(segments * 16), trailTimes = new Float64Array(segments);
    let o = 0;
    for (let k = 0; k < segments; k++) {
      const g = order[k], b = bodies[owner[g]], i = start[g], c = ramp(seg[g] / top), p = b.pos, t = ends[g];
      trailTimes[k] = t;
      for (const j of [i, i + 1]) { trail.set([p[3 * j], p[3 * j + 1], p[3 * j + 2] + 0.05, c[0], c[1], c[2], 0.95, t], o); o += 8; }
    }
    const lineDraw = (values, times, perItem) => values.length ? { vao: vertexArray(staticBuffer(values),
      [[0, 3, 8, 0], [1, 4, 8, 3], [2, 1, 8, 7]]), count: values.length / 8, total: values.length / 8,
      times: times || null, perItem: perItem || 1 } : null;
    draws.grid = lineDraw(new Float32Array(grid));
    draws.trails = lineDraw(trail, trailTimes, 2);
    // Events: a point each, where and when it happened: a ring as it happens, then a dot that stays
    // for landings, take-offs and collisions (alpha 1 keeps it; other events fade).
    const n = events.t.length, points = new Float32Array(8 * n), eventTimes = new Float64Array(n);
    const byTime = Array.from({ length: n }, (_, k) => k).sort((a, b) => events.t[a] - events.t[b] || a - b);
    for (let k = 0; k < n; k++) {
      const i = byTime[k], text = events.strings[events.text[i]], c = eventColour(text), p = events.position;
      const keep = EVENT_COLOURS[eventKind(text)] ? 1 : 0;
      points.set([p[3 * i], p[3 * i + 1], p[3 * i + 2] + 0.3, c[0], c[1], c[2], keep, events.t[i]], 8 * k);
      eventTimes[k] = events.t[i];
    }
    draws.events = lineDraw(points, eventTimes, 1);
    // Bodies: their spheres and cylinders, placed every frame.
    let spheres = 0, cylinders = 0;
    for (const b of bodies) { spheres += b.spheres.length; cylinders += b.cylinders.length; }
    draws.bodySpheres = spheres ? instanced(unitSphere(), new Float32Array(9 * spheres), true) : null;
    draws.bodyCylinders = cylinders ? instanced(unitCylinder(), new Float32Array(9 * cylinders), true) : null;
    const present = (list) => list.filter((d) => d);
    opaque = present([draws.terrain, draws.solids]);
    staticInst = present([draws.cylinders, draws.spheres]);
    bodyInst = present([draws.bodySpheres, draws.bodyCylinders]);
    lines = present([draws.grid, draws.trails]);
    translucent = present([draws.rooms, draws.shells]);
  }

  function niceCeil(v) {
    const p = Math.pow(10, Math.floor(Math.log10(v)));
    for (const m of [1, 2, 2.5, 5, 10]) if (m * p >= v) return m * p;
    return 10 * p;
  }
  function ramp(f) {
    const stops = [[0.15, 0.27, 0.85], [0.12, 0.78, 0.85], [0.22, 0.82, 0.24], [0.95, 0.89, 0.16], [0.91, 0.2, 0.12]];
    const x = Math.min(0.999, Math.max(0, f)) * (stops.length - 1), i = Math.floor(x), u = x - i;
    return [0, 1, 2].map((k) => stops[i][k] + (stops[i + 1][k] - stops[i][k]) * u);
  }

  // ---- camera and frame ------------------------------------------------------------------------
  const viewProj = new Float32Array(16);
  function computeViewProj(aspect) {
    const c = camera, cp = Math.cos(c.pitch);
    const eye = [c.target[0] + c.dist * cp * Math.cos(c.yaw), c.target[1] + c.dist * cp * Math.sin(c.yaw),
      c.target[2] + c.dist * Math.sin(c.pitch)];
    let fx = c.target[0] - eye[0], fy = c.target[1] - eye[1], fz = c.target[2] - eye[2];
    let l = Math.hypot(fx, fy, fz); fx /= l; fy /= l; fz /= l;
    let sx = fy, sy = -fx, sz = 0;  // f x up(0,0,1)
    l = Math.hypot(sx, sy) || 1; sx /= l; sy /= l;
    const ux = sy * fz - sz * fy, uy = sz * fx - sx * fz, uz = sx * fy - sy * fx;
    const near = Math.max(0.05, c.dist * 0.01), far = c.dist * 20 + 2000, f = 1 / Math.tan(FOV / 2);
    const a = f / aspect, nf = 1 / (near - far);
    const view = [sx, ux, -fx, 0, sy, uy, -fy, 0, sz, uz, -fz, 0,
      -(sx * eye[0] + sy * eye[1] + sz * eye[2]), -(ux * eye[0] + uy * eye[1] + uz * eye[2]),
      fx * eye[0] + fy * eye[1] + fz * eye[2], 1];
    const proj = [a, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) * nf, -1, 0, 0, 2 * far * near * nf, 0];
    for (let col = 0; col < 4; col++) for (let row = 0; row < 4; row++) {
      let sum = 0;
      for (let k = 0; k < 4; k++) sum += proj[4 * k + row] * view[4 * col + k];
      viewProj[4 * col + row] = sum;
    }
  }

  const scratch = [0, 0, 0];
  function placeBodies() {
    let si = 0, ci = 0;
    const sv = draws.bodySpheres && draws.bodySpheres.values, cv = draws.bodyCylinders && draws.bodyCylinders.values;
    for (let bi = 0; bi < bodies.length; bi++) {
      const b = bodies[bi];
      place(b, time);
      const col = b.colour, sel = bi === selected;
      const r = sel ? 1 : col[0], g = sel ? 1 : col[1], bl = sel ? 1 : col[2];
      for (let k = 0; k < b.spheres.length; k++) {
        const s = b.spheres[k];
        rotate(b.q, s[0], s[1], s[2], scratch);
        const radius = b.visible ? s[3] : 0;
        sv[si] = b.at[0] + scratch[0]; sv[si + 1] = b.at[1] + scratch[1]; sv[si + 2] = b.at[2] + scratch[2];
        sv[si + 3] = radius; sv[si + 4] = radius; sv[si + 5] = r; sv[si + 6] = g; sv[si + 7] = bl; sv[si + 8] = 1;
        si += 9;
      }
      for (let k = 0; k < b.cylinders.length; k++) {
        const c = b.cylinders[k];
        rotate(b.q, c[0], c[1], c[2], scratch);
        cv[ci] = b.at[0] + scratch[0]; cv[ci + 1] = b.at[1] + scratch[1]; cv[ci + 2] = b.at[2] + scratch[2];
        cv[ci + 3] = b.visible ? c[3] : 0; cv[ci + 4] = b.visible ? c[4] : 0;
        cv[ci + 5] = r; cv[ci + 6] = g; cv[ci + 7] = bl; cv[ci + 8] = 1;
        ci += 9;
      }
    }
    if (draws.bodySpheres) { gl.bindBuffer(gl.ARRAY_BUFFER, draws.bodySpheres.inst); gl.bufferSubData(gl.ARRAY_BUFFER, 0, sv); }
    if (draws.bodyCylinders) { gl.bindBuffer(gl.ARRAY_BUFFER, draws.bodyCylinders.inst); gl.bufferSubData(gl.ARRAY_BUFFER, 0, cv); }
  }

  // What render draws, in order (set once the scene is built): no arrays made per frame.
  let opaque = [], staticInst = [], bodyInst = [], lines = [], translucent = [];
  const FOV = 0.9, MIN_BODY_PIXELS = 3;
  const LIGHT = (() => { const l = [0.45, -0.35, 0.82], n = Math.hypot(...l); return l.map((v) => v / n); })();
  function useLit(p) {
    gl.useProgram(p.program);
    gl.uniformMatrix4fv(p.uViewProj, false, viewProj);
    gl.uniform3f(p.uLight, LIGHT[0], LIGHT[1], LIGHT[2]);
  }
  function drawList(list, mode) {
    for (let k = 0; k < list.length; k++) {
      const d = list[k];
      if (!d.count) continue;
      gl.bindVertexArray(d.vao);
      if (d.instances !== undefined) gl.drawElementsInstanced(gl.TRIANGLES, d.count, gl.UNSIGNED_SHORT, 0, d.instances);
      else gl.drawArrays(mode, 0, d.count);
    }
  }

  // How many of a draw's time-sorted items are reached at `time` (binary search).
  function reached(d) {
    const ts = d.times;
    let lo = 0, hi = ts.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (ts[mid] <= time + 1e-9) lo = mid + 1; else hi = mid; }
    return lo * d.perItem;
  }

  function render() {
    const started = performance.now();
    if (draws.trails) draws.trails.count = reached(draws.trails);
    if (draws.events) draws.events.count = reached(draws.events);
    const canvas = gl.canvas, ratio = window.devicePixelRatio || 1;
    const w = Math.max(1, Math.round(canvas.clientWidth * ratio)), h = Math.max(1, Math.round(canvas.clientHeight * ratio));
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    placeBodies();
    if (ui.follow.checked && selected >= 0 && bodies[selected].visible) {
      const at = bodies[selected].at;
      camera.target[0] = at[0]; camera.target[1] = at[1]; camera.target[2] = at[2];
    }
    computeViewProj(w / h);
    gl.viewport(0, 0, w, h);
    gl.clearColor(0.53, 0.66, 0.8, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    gl.disable(gl.BLEND);
    gl.depthMask(true);
    useLit(progs.mesh);
    drawList(opaque, gl.TRIANGLES);
    useLit(progs.inst);
    gl.uniform1f(progs.inst.uMinScale, 0);
    drawList(staticInst, gl.TRIANGLES);
    gl.uniform1f(progs.inst.uMinScale, MIN_BODY_PIXELS * 2 * Math.tan(FOV / 2) / h);
    drawList(bodyInst, gl.TRIANGLES);
    gl.enable(gl.BLEND);
    gl.blendFunc(gl.SRC_ALPHA, gl.ONE_MINUS_SRC_ALPHA);
    gl.useProgram(progs.line.program);
    gl.uniformMatrix4fv(progs.line.uViewProj, false, viewProj);
    gl.uniform1f(progs.line.uTime, time + 1e-9);
    drawList(lines, gl.LINES);
    gl.depthMask(false);
    useLit(progs.mesh);
    drawList(translucent, gl.TRIANGLES);
    if (draws.events && draws.events.count) {
      gl.useProgram(progs.point.program);
      gl.uniformMatrix4fv(progs.point.uViewProj, false, viewProj);
      gl.uniform1f(progs.point.uTime, time + 1e-9);
      gl.uniform1f(progs.point.uScale, ratio);
      gl.bindVertexArray(draws.events.vao);
      gl.drawArrays(gl.POINTS, 0, draws.events.count);
    }
    gl.depthMask(true);
    gl.bindVertexArray(null);
    viewer.frames++;
    dirty = false;
    updatePanel();
    const ms = performance.now() - started;
    viewer.frameMs = viewer.frames === 1 ? ms : 0.9 * viewer.frameMs + 0.1 * ms;
    if (viewer.frames % 30 === 1) { root.dataset.frames = String(viewer.frames); root.dataset.frameMs = viewer.frameMs.toFixed(2); }
  }

  // Where body `index` is drawn now (the middle of its spheres and cylinders), in page pixels
  // (null when hidden or behind the eye).
  function screenPosition(index) {
    const b = bodies[index];
    if (!b || !b.visible) return null;
    const shapes = b.spheres.concat(b.cylinders), mid = [0, 0, 0];
    for (const s of shapes) {
      rotate(b.q, s[0], s[1], s[2] + (s.length === 5 ? s[4] / 2 : 0), scratch);
      for (let k = 0; k < 3; k++) mid[k] += (b.at[k] + scratch[k]) / shapes.length;
    }
    return project(shapes.length ? mid : b.at);
  }
  // Where the scene point p is drawn, in page pixels (null behind the eye).
  function project(p) {
    if (!gl) return null;
    const m = viewProj, v = [0, 0, 0, 0];
    for (let r = 0; r < 4; r++) v[r] = m[r] * p[0] + m[4 + r] * p[1] + m[8 + r] * p[2] + m[12 + r];
    if (v[3] <= 0) return null;
    const box = gl.canvas.getBoundingClientRect();
    return [box.left + (v[0] / v[3] * 0.5 + 0.5) * box.width, box.top + (0.5 - v[1] / v[3] * 0.5) * box.height];
  }

  // ---- time and controls -------------------------------------------------------------------------
  function setTime(t, fromSlider) {
    const value = Number(t);
    if (!Number.isFinite(value)) return time;
    time = Math.min(t1, Math.max(t0, value));
    viewer.time = time;
    root.dataset.time = time.toFixed(4);
    if (!fromSlider) ui.slider.value = String(time);
    if (gl) render();
    return time;
  }
  function setPlaying(on) {
    playing = !!on && bodies.length > 0;
    if (playing && time >= t1) setTime(t0);
    ui.play.textContent = playing ? '\u275a\u275a' : '\u25b6';
    lastClock = performance.now();
  }
  function tick(now) {
    if (playing) {
      const next = time + (now - lastClock) / 1000 * speed;
      if (next >= t1) { setTime(t1); setPlaying(false); } else setTime(next);
    } else if (dirty) render();
    lastClock = now;
    requestAnimationFrame(tick);
  }
  // #t=SECONDS&body=NAME&follow=1&play=1&speed=2: what the address asks for.
  function hashOption(name) {
    for (const part of location.hash.replace(/^#/, '').split('&')) {
      const eq = part.indexOf('=');
      if (eq > 0 && part.slice(0, eq) === name) {
        try { return decodeURIComponent(part.slice(eq + 1)); } catch (e) { return null; }
      }
    }
    return null;
  }
  function hashTime() {
    const t = hashOption('t');
    return t !== null && t.trim() !== '' && Number.isFinite(Number(t)) ? Number(t) : null;
  }
  function applyHash() {
    const name = hashOption('body');
    if (name !== null) select(bodies.findIndex((b) => b.name === name));
    if (hashOption('follow') !== null) { ui.follow.checked = hashOption('follow') === '1'; dirty = true; }
    const rate = Number(hashOption('speed'));
    if (rate > 0) { speed = rate; ui.speed.value = String(rate); }
    const t = hashTime();
    if (t !== null) setTime(t);
    if (hashOption('play') === '1') setPlaying(true);
  }

  function select(index) {
    selected = index >= 0 && index < bodies.length ? index : -1;
    for (const li of $('body-list').children) li.classList.toggle('selected', Number(li.dataset.index) === selected);
    shownRecord = '';
    drawMarks();
    if (gl) render();
    return selected >= 0 ? bodies[selected].name : null;
  }

  function fillBodyList() {
    const list = $('body-list'), filter = $('filter').value.toLowerCase();
    list.textContent = '';
    const limit = 2000;
    let shown = 0;
    for (let i = 0; i < bodies.length && shown < limit; i++) {
      const b = bodies[i];
      if (filter && !b.name.toLowerCase().includes(filter)) continue;
      const li = document.createElement('li'), dot = document.createElement('i');
      dot.style.background = 'rgb(' + b.colour.map((c) => Math.round(255 * c)).join(',') + ')';
      li.appendChild(dot);
      li.appendChild(document.createTextNode(b.name));
      li.dataset.index = String(i);
      li.title = b.name;
      if (i === selected) li.classList.add('selected');
      list.appendChild(li);
      shown++;
    }
  }

  const fmt = (v, d) => Number.isFinite(v) ? v.toFixed(d) : '-';
  const vec = (a, i, n, d) => { const out = []; for (let k = 0; k < n; k++) out.push(fmt(a[n * i + k], d)); return out.join('  '); };
  function updatePanel() {
    ui.clock.textContent = time.toFixed(3) + ' s / ' + t1.toFixed(3) + ' s';
    const table = ui.inspector;
    if (selected < 0) {
      if (shownRecord !== 'none') { shownRecord = 'none'; rows(table, [['', 'select a body in the list']]); }
      return;
    }
    const b = bodies[selected], i = recordAt(b, time), key = selected + ':' + i;
    if (key === shownRecord) return;
    shownRecord = key;
    if (i < 0) { rows(table, [['body', b.name], ['', 'no record yet']]); return; }
    const c = b.c, names = data.tables.transient, flags = [];
    for (let k = 0; k < names.length; k++) if (c.transient[i] & (1 << k)) flags.push(names[k]);
    const m = c.motion[i] >= 0 ? data.tables.motion[c.motion[i]] : null;
    const speedOf = (v) => Math.hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2]);
    const out = [
      ['body', b.name], ['id', b.id || '-'],
      ['record', (i + 1) + ' of ' + b.n + (b.stride > 1 ? ' (every ' + b.stride + 'th)' : '')],
      ['t', fmt(c.t[i], 4) + ' s'], ['quantum', fmt(c.quantum[i], 4) + ' s'],
      ['cell', '0x' + c.cell[i].toString(16).toUpperCase().padStart(8, '0')],
      ['origin', vec(c.origin, i, 3, 3)], ['scene x y z', vec(b.pos, i, 3, 3)],
      ['orientation', vec(c.orientation, i, 4, 4)], ['heading', fmt(c.heading[i], 1) + '\u00b0'],
      ['velocity', vec(c.velocity, i, 3, 3) + '  |' + fmt(speedOf(c.velocity), 3) + '|'],
      ['cached vel.', vec(c.cached_velocity, i, 3, 3)], ['omega', vec(c.omega, i, 3, 3)],
      ['transient', flags.join(' ') || '-'],
      ['contact', Number.isFinite(c.contact_normal[3 * i]) ? vec(c.contact_normal, i, 3, 3) : '-'],
    ];
    if (m) {
      const cmd = (k) => m[k] == null ? '-' : m[k] + ' \u00d7' + fmt(m[k + '_speed'], 2);
      out.push(['style', String(m.style)], ['forward', cmd('forward')], ['sidestep', cmd('sidestep')],
        ['turn', cmd('turn')], ['hold key', String(m.hold_key)],
        ['animation', m.animation == null ? '-' : m.animation + ' @' + fmt(c.frame[i], 2)]);
    } else out.push(['motion', '-']);
    const mine = b.events;
    let upto = 0;
    while (upto < mine.length && events.t[mine[upto]] <= c.t[i] + 1e-9) upto++;
    const recent = mine.slice(Math.max(0, upto - 8), upto).reverse().map((e) => fmt(events.t[e], 3) + '  ' + events.strings[events.text[e]]);
    out.push(['events', recent.length ? recent.join('\n') : '-']);
    rows(table, out);
  }
  function rows(table, list) {
    while (table.rows.length > list.length) table.deleteRow(-1);
    for (let i = 0; i < list.length; i++) {
      let tr = table.rows[i];
      if (!tr) {
        tr = table.insertRow();
        tr.appendChild(document.createElement('th'));
        tr.appendChild(document.createElement('td')).style.whiteSpace = 'pre-wrap';
      }
      if (tr.cells[0].textContent !== list[i][0]) tr.cells[0].textContent = list[i][0];
      if (tr.cells[1].textContent !== list[i][1]) tr.cells[1].textContent = list[i][1];
    }
  }

  function drawMarks() {
    const canvas = $('marks'), ratio = window.devicePixelRatio || 1;
    canvas.width = Math.max(1, Math.round(canvas.clientWidth * ratio));
    canvas.height = Math.max(1, Math.round(canvas.clientHeight * ratio));
    const ctx = canvas.getContext('2d'), w = canvas.width, h = canvas.height, pad = 8 * ratio;
    ctx.clearRect(0, 0, w, h);
    ctx.fillStyle = 'rgba(255,255,255,0.08)';
    ctx.fillRect(pad, h - 2 * ratio, w - 2 * pad, 2 * ratio);
    if (!events || t1 <= t0) return;
    for (let e = 0; e < events.t.length; e++) {
      const mine = events.body[e] === selected, c = eventColour(events.strings[events.text[e]]);
      if (selected >= 0 && !mine && events.t.length > 2000) continue;
      const x = pad + (events.t[e] - t0) / (t1 - t0) * (w - 2 * pad);
      ctx.fillStyle = 'rgba(' + c.map((v) => Math.round(255 * v)).join(',') + ',' + (mine || selected < 0 ? 1 : 0.35) + ')';
      ctx.fillRect(Math.round(x) - ratio, mine ? 0 : h * 0.35, 2 * ratio, mine ? h : h * 0.65);
    }
  }

  function frameAll() {
    let lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (const b of bodies) for (let i = 0; i < b.n; i++) for (let k = 0; k < 3; k++) {
      lo[k] = Math.min(lo[k], b.pos[3 * i + k]); hi[k] = Math.max(hi[k], b.pos[3 * i + k]);
    }
    if (!Number.isFinite(lo[0])) { lo = [0, 0, 0]; hi = [192, 192, 0]; }
    camera.target = [0, 1, 2].map((k) => (lo[k] + hi[k]) / 2);
    const extent = Math.max(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
    camera.dist = Math.min(5000, extent * 1.1 + 28);
  }

  function wireControls() {
    const canvas = gl.canvas;
    let drag = null;
    canvas.addEventListener('contextmenu', (e) => e.preventDefault());
    canvas.addEventListener('pointerdown', (e) => {
      drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey };
      canvas.setPointerCapture(e.pointerId);
    });
    canvas.addEventListener('pointermove', (e) => {
      if (!drag) return;
      const dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      drag.x = e.clientX; drag.y = e.clientY;
      if (drag.pan) {
        // Grab the ground: right drags the scene right, down pulls it toward the eye.
        const s = camera.dist * 0.0015, cy = Math.cos(camera.yaw), sy = Math.sin(camera.yaw);
        camera.target[0] += (dx * sy - dy * cy) * s;
        camera.target[1] += (-dx * cy - dy * sy) * s;
      } else {
        camera.yaw -= dx * 0.006;
        camera.pitch = Math.min(1.55, Math.max(0.03, camera.pitch + dy * 0.006));
      }
      dirty = true;
    });
    canvas.addEventListener('pointerup', () => { drag = null; });
    canvas.addEventListener('wheel', (e) => {
      e.preventDefault();
      camera.dist = Math.min(20000, Math.max(0.5, camera.dist * Math.exp(e.deltaY * 0.0012)));
      dirty = true;
    }, { passive: false });
    canvas.addEventListener('dblclick', () => {
      if (selected >= 0 && bodies[selected].visible) { camera.target = bodies[selected].at.slice(); camera.dist = 12; dirty = true; }
    });
    $('play').addEventListener('click', () => setPlaying(!playing));
    $('speed').addEventListener('change', (e) => { speed = Number(e.target.value) || 1; });
    $('slider').addEventListener('input', (e) => setTime(e.target.value, true));
    $('marks').addEventListener('click', (e) => {
      const r = e.target.getBoundingClientRect();
      setTime(t0 + (e.clientX - r.left - 8) / Math.max(1, r.width - 16) * (t1 - t0));
    });
    $('body-list').addEventListener('click', (e) => {
      const li = e.target.closest('li');
      if (li) select(Number(li.dataset.index) === selected ? -1 : Number(li.dataset.index));
    });
    $('filter').addEventListener('input', fillBodyList);
    $('follow').addEventListener('change', () => { dirty = true; });
    window.addEventListener('resize', () => { drawMarks(); dirty = true; });
    window.addEventListener('hashchange', applyHash);
    window.addEventListener('keydown', (e) => {
      if ((e.target.tagName === 'INPUT' && e.target.type !== 'range') || e.target.tagName === 'SELECT') return;
      if (e.key === ' ') { e.preventDefault(); setPlaying(!playing); }
      if (e.key === 'ArrowLeft' || e.key === 'ArrowRight') {
        e.preventDefault();
        setPlaying(false);
        setTime(time + (e.key === 'ArrowLeft' ? -1 : 1) / 30);
      }
    });
  }

  async function start() {
    for (const id of ['follow', 'slider', 'clock', 'inspector', 'speed', 'play']) ui[id] = $(id);
    data = JSON.parse($('acphys-data').textContent);
    $('title').textContent = data.title;
    for (const text of data.notes) note(text);
    buffer = await inflate($('acphys-blob').textContent);
    prepareBodies();
    t0 = data.time[0]; t1 = data.time[1];
    const slider = $('slider');
    slider.min = String(t0); slider.max = String(t1);
    gl = $('scene').getContext('webgl2', { antialias: true, preserveDrawingBuffer: true });
    if (!gl) throw new Error('this browser has no WebGL2');
    progs = {
      mesh: program(MESH_VS, LIT_FS, ['uViewProj', 'uLight']),
      inst: program(INST_VS, LIT_FS, ['uViewProj', 'uLight', 'uMinScale']),
      line: program(LINE_VS, LINE_FS, ['uViewProj', 'uTime']),
      point: program(POINT_VS, POINT_FS, ['uViewProj', 'uTime', 'uScale']),
    };
    buildScene();
    frameAll();
    fillBodyList();
    wireControls();
    drawMarks();
    setTime(t0);
    applyHash();
    viewer.ready = true;
    root.dataset.state = 'ready';
    requestAnimationFrame((now) => { lastClock = now; requestAnimationFrame(tick); });
  }
  start().catch((e) => fail(String((e && e.message) || e)));
})();
