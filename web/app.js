// The page (docs/web.md): builds the face in WebAssembly from face.myoweb, steps it in real time,
// draws its skin with WebGL2 (positions uploaded each frame) and exposes window.myoshell for tests
// and embedding.
'use strict';

const hook = (window.myoshell = { ready: false, error: null });
const pageStart = performance.now();

function message(Module, e) {
  // A C++ exception reaches JavaScript as the address of the exception object.
  if (typeof e === 'number' && Module) return Module.exceptionMessage(e);
  return e && e.message ? e.message : String(e);
}

function list(v) {  // an embind vector as a JavaScript array
  const out = [];
  for (let i = 0; i < v.size(); ++i) out.push(v.get(i));
  v.delete();
  return out;
}

// --- WebGL2 -------------------------------------------------------------------------------------
const VS = `#version 300 es
in vec3 position;
uniform mat4 viewProjection;
out vec3 world;
void main() { world = position; gl_Position = viewProjection * vec4(position, 1.0); }`;
const FS = `#version 300 es
precision highp float;
in vec3 world;
out vec4 colour;
void main() {
  // The face's normal from the screen-space derivatives of the position: no normals to upload.
  vec3 n = normalize(cross(dFdx(world), dFdy(world)));
  vec3 light = normalize(vec3(0.3, 0.5, 1.0));
  float d = max(dot(n, light), 0.0);
  vec3 skin = vec3(0.85, 0.66, 0.56);
  colour = vec4(skin * (0.25 + 0.75 * d), 1.0);
}`;

// The modes as morph targets: the skin reconstructed on the GPU, rest + Σⱼ qⱼ Φⱼ, Φ read from a float
// texture (texel i·d + j holds vertex i's row of mode j), q a uniform array: only d floats uploaded a
// frame. No placement (the jaw's turn, the lids, the contact projection): docs/web.md.
const TEXTURE_WIDTH = 4096;
const VS_MORPH = (d) => `#version 300 es
precision highp float;
precision highp sampler2D;
in vec3 position;
uniform mat4 viewProjection;
uniform sampler2D modes;
uniform vec4 q[${Math.ceil(d / 4)}];
out vec3 world;
void main() {
  vec3 p = position;
  int base = gl_VertexID * ${d};
  for (int j = 0; j < ${d}; ++j) {
    int k = base + j;
    p += q[j / 4][j % 4] * texelFetch(modes, ivec2(k % ${TEXTURE_WIDTH}, k / ${TEXTURE_WIDTH}), 0).rgb;
  }
  world = p;
  gl_Position = viewProjection * vec4(p, 1.0);
}`;

function program(gl, vs, fs) {
  const prog = gl.createProgram();
  gl.attachShader(prog, compile(gl, gl.VERTEX_SHADER, vs));
  gl.attachShader(prog, compile(gl, gl.FRAGMENT_SHADER, fs));
  gl.linkProgram(prog);
  if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
  return prog;
}

function compile(gl, type, text) {
  const s = gl.createShader(type);
  gl.shaderSource(s, text);
  gl.compileShader(s);
  if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
  return s;
}

function perspective(fovy, aspect, near, far) {
  const f = 1 / Math.tan(fovy / 2);
  return [f / aspect, 0, 0, 0, 0, f, 0, 0, 0, 0, (far + near) / (near - far), -1, 0, 0, (2 * far * near) / (near - far), 0];
}

function multiply(a, b) {  // column-major 4×4
  const o = new Array(16).fill(0);
  for (let c = 0; c < 4; ++c)
    for (let r = 0; r < 4; ++r)
      for (let k = 0; k < 4; ++k) o[c * 4 + r] += a[k * 4 + r] * b[c * 4 + k];
  return o;
}

class Drawing {
  constructor(canvas, Module, page) {
    const gl = (this.gl = canvas.getContext('webgl2', { antialias: true }));
    if (!gl) throw new Error('this browser gives no WebGL2 context');
    this.Module = Module;
    this.page = page;
    this.n = page.vertexCount();
    const prog = (this.prog = gl.createProgram());
    gl.attachShader(prog, compile(gl, gl.VERTEX_SHADER, VS));
    gl.attachShader(prog, compile(gl, gl.FRAGMENT_SHADER, FS));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
    this.vao = gl.createVertexArray();
    gl.bindVertexArray(this.vao);
    this.positions = gl.createBuffer();
    gl.bindBuffer(gl.ARRAY_BUFFER, this.positions);
    gl.bufferData(gl.ARRAY_BUFFER, this.n * 12, gl.DYNAMIC_DRAW);
    const loc = gl.getAttribLocation(prog, 'position');
    gl.enableVertexAttribArray(loc);
    gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
    const count = 3 * page.triangleCount();
    const tri = new Uint32Array(Module.HEAPU32.buffer, page.trianglesAddress(), count).slice();
    const ib = (this.indices = gl.createBuffer());
    gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, ib);
    gl.bufferData(gl.ELEMENT_ARRAY_BUFFER, tri, gl.STATIC_DRAW);
    this.count = count;
    // Frame the rest face: its bounding box's centre, seen from the front (+z) at a distance that fits it.
    const p = this.shape();
    this.rest = p.slice();  // the positions at load are the rest's
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let i = 0; i < p.length; i += 3)
      for (let c = 0; c < 3; ++c) { lo[c] = Math.min(lo[c], p[i + c]); hi[c] = Math.max(hi[c], p[i + c]); }
    this.centre = lo.map((v, c) => (v + hi[c]) / 2);
    this.radius = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2;
    this.yaw = 0.35;
    this.pitch = 0.05;
  }

  // The native renderer's front view of the rest face on a square canvas of `size` CSS pixels (null:
  // back to the page's own view).
  setPicture(size, frame, rest) {
    const canvas = this.gl.canvas;
    if (!size) { this.picture = null; canvas.style.width = canvas.style.height = ''; return; }
    canvas.style.width = canvas.style.height = `${size}px`;
    const right = frame.slice(3, 6), up = frame.slice(6, 9), z = frame.slice(9, 12);
    const forward = z.map((v) => -v);
    const dot = (a, i) => a[0] * rest[3 * i] + a[1] * rest[3 * i + 1] + a[2] * rest[3 * i + 2];
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity, z0 = Infinity, z1 = -Infinity;
    for (let i = 0; i < this.n; ++i) {
      const x = dot(right, i), y = dot(up, i), d = dot(forward, i);
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
      z0 = Math.min(z0, d); z1 = Math.max(z1, d);
    }
    const height = Math.max(y1 - y0, x1 - x0) / (1 - 2 * 0.04);  // fitToBounds, aspect 1
    this.picture = { right, up, forward, cx: (x0 + x1) / 2, cy: (y0 + y1) / 2, cz: (z0 + z1) / 2,
                     halfW: height / 2, halfH: height / 2 };
  }

  // The vertex under the pixel (x, y) (CSS pixels from the canvas's corner): the nearest to the eye
  // of those drawn within 10 pixels, and its eye depth; null when none.
  pick(x, y) {
    const m = this.viewProjection, p = this.shape(), canvas = this.gl.canvas;
    if (!m) return null;
    const w = canvas.clientWidth, h = canvas.clientHeight;
    let best = null;
    for (let i = 0; i < this.n; ++i) {
      const X = p[3 * i], Y = p[3 * i + 1], Z = p[3 * i + 2];
      const cw = m[3] * X + m[7] * Y + m[11] * Z + m[15];
      const sx = ((m[0] * X + m[4] * Y + m[8] * Z + m[12]) / cw * 0.5 + 0.5) * w;
      const sy = (0.5 - (m[1] * X + m[5] * Y + m[9] * Z + m[13]) / cw * 0.5) * h;
      if ((sx - x) ** 2 + (sy - y) ** 2 > 100) continue;
      if (!best || cw < best.depth) best = { vertex: i, depth: cw };
    }
    return best;
  }

  // Switches to the modes reconstructed on the GPU (true) or positions uploaded (false). The texture
  // of Φ is made on the first switch.
  setGpuMorph(on) {
    const gl = this.gl, page = this.page, Module = this.Module;
    if (on && !this.morph) {
      const d = page.modeCount(), n = this.n, texels = n * d, h = Math.ceil(texels / TEXTURE_WIDTH);
      const phi = new Float32Array(TEXTURE_WIDTH * h * 3);
      phi.set(new Float32Array(Module.HEAPF32.buffer, page.morphTargetsAddress(), texels * 3));
      const prog = program(gl, VS_MORPH(d), FS);
      const vao = gl.createVertexArray();
      gl.bindVertexArray(vao);
      const rest = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, rest);
      gl.bufferData(gl.ARRAY_BUFFER, this.rest, gl.STATIC_DRAW);
      const loc = gl.getAttribLocation(prog, 'position');
      gl.enableVertexAttribArray(loc);
      gl.vertexAttribPointer(loc, 3, gl.FLOAT, false, 0, 0);
      gl.bindBuffer(gl.ELEMENT_ARRAY_BUFFER, this.indices);
      const tex = gl.createTexture();
      gl.bindTexture(gl.TEXTURE_2D, tex);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGB32F, TEXTURE_WIDTH, h, 0, gl.RGB, gl.FLOAT, phi);
      this.morph = { prog, vao, tex, d, q: new Float32Array(4 * Math.ceil(d / 4)) };
    }
    this.gpu = !!on;
    page.setPlaceOnCpu(!on);
  }

  shape() {  // the module's float32 positions (the view is remade: memory may have grown)
    return new Float32Array(this.Module.HEAPF32.buffer, this.page.positionsAddress(), 3 * this.n);
  }

  draw() {
    const gl = this.gl, canvas = gl.canvas;
    const w = canvas.clientWidth * devicePixelRatio, h = canvas.clientHeight * devicePixelRatio;
    if (canvas.width !== w || canvas.height !== h) { canvas.width = w; canvas.height = h; }
    gl.viewport(0, 0, canvas.width, canvas.height);
    gl.clearColor(0.13, 0.14, 0.15, 1);
    gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
    gl.enable(gl.DEPTH_TEST);
    let prog = this.prog;
    if (this.gpu) {
      // d weights a frame instead of n positions.
      const m = this.morph;
      prog = m.prog;
      gl.useProgram(prog);
      gl.bindVertexArray(m.vao);
      m.q.set(new Float32Array(this.Module.HEAPF32.buffer, this.page.modalCoordinatesAddress(), m.d));
      gl.uniform4fv(gl.getUniformLocation(prog, 'q'), m.q);
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, m.tex);
      gl.uniform1i(gl.getUniformLocation(prog, 'modes'), 0);
    } else {
      gl.useProgram(prog);
      gl.bindVertexArray(this.vao);
      gl.bindBuffer(gl.ARRAY_BUFFER, this.positions);
      gl.bufferSubData(gl.ARRAY_BUFFER, 0, this.shape());
    }
    if (this.picture) {
      // The native renderer's front view (render/face_picture.cpp, framing "all"): orthographic along
      // the face frame's −z, fitted to the rest face's extent on its x and y with a 4 % margin.
      const { right: r, up: u, forward: f, cx, cy, cz, halfW, halfH } = this.picture;
      const D = 100;  // cm of depth either side of the centre
      const vp = [r[0] / halfW, u[0] / halfH, f[0] / D, 0, r[1] / halfW, u[1] / halfH, f[1] / D, 0,
                  r[2] / halfW, u[2] / halfH, f[2] / D, 0, -cx / halfW, -cy / halfH, -cz / D, 1];
      this.viewProjection = vp;
      gl.uniformMatrix4fv(gl.getUniformLocation(prog, 'viewProjection'), false, vp);
      gl.drawElements(gl.TRIANGLES, this.count, gl.UNSIGNED_INT, 0);
      return;
    }
    const dist = 2.6 * this.radius;
    const [cx, cy, cz] = this.centre;
    const cyw = Math.cos(this.yaw), syw = Math.sin(this.yaw), cp = Math.cos(this.pitch), sp = Math.sin(this.pitch);
    // view = translate(0,0,-dist) · Rx(pitch) · Ry(-yaw) · translate(-centre)
    const ry = [cyw, 0, syw, 0, 0, 1, 0, 0, -syw, 0, cyw, 0, 0, 0, 0, 1];
    const rx = [1, 0, 0, 0, 0, cp, -sp, 0, 0, sp, cp, 0, 0, 0, 0, 1];
    const t = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, -cx, -cy, -cz, 1];
    const back = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -dist, 1];
    const view = multiply(back, multiply(rx, multiply(ry, t)));
    const proj = perspective(0.7, canvas.width / canvas.height, dist / 10, dist * 10);
    this.viewProjection = multiply(proj, view);
    // The camera's right and up axes in head space (rows of the view's rotation) and the focal scale:
    // a pixel at eye depth w spans 2 w tan(fovy/2) / height cm.
    this.right = [cyw, 0, -syw];
    this.up = [-sp * syw, cp, -sp * cyw];
    this.pixelScale = (2 * Math.tan(0.35)) / canvas.height;
    gl.uniformMatrix4fv(gl.getUniformLocation(prog, 'viewProjection'), false, this.viewProjection);
    gl.drawElements(gl.TRIANGLES, this.count, gl.UNSIGNED_INT, 0);
  }
}

// --- the page -----------------------------------------------------------------------------------
async function main() {
  const status = document.getElementById('status');
  let Module = null;
  try {
    Module = await createMyoshell();
    const response = await fetch('face.myoweb');
    if (!response.ok) throw new Error('face.myoweb: HTTP ' + response.status);
    const bytes = new Uint8Array(await response.arrayBuffer());
    let page;
    try {
      page = new Module.Page(bytes);
    } catch (e) {
      throw new Error(message(Module, e));
    }
    const drawing = new Drawing(document.getElementById('canvas'), Module, page);
    const names = list(page.muscleNames());
    const sliders = {};
    const box = document.getElementById('muscles');
    // A labelled slider over [0, 1] in `parent`, calling `set` with its value.
    const addSlider = (parent, text, set) => {
      const label = document.createElement('label');
      label.className = 'slider';
      label.textContent = text;
      const input = document.createElement('input');
      Object.assign(input, { type: 'range', min: 0, max: 1, step: 0.01, value: 0 });
      input.addEventListener('input', () => set(Number(input.value)));
      label.appendChild(input);
      parent.appendChild(label);
      return input;
    };
    for (const name of [...names].sort())
      sliders[name] = addSlider(box, name.replace(/_/g, ' '), (x) => page.setActivation(name, x));
    const call = (f) => { try { return f(); } catch (e) { throw new Error(message(Module, e)); } };
    const gravity = document.getElementById('gravity');
    gravity.addEventListener('change', () => page.setGravity(gravity.checked));
    const gpu = document.getElementById('gpu');
    gpu.addEventListener('change', () => call(() => drawing.setGpuMorph(gpu.checked)));
    const pitch = document.getElementById('pitch');
    pitch.addEventListener('input', () => page.setHeadPitch(Number(pitch.value)));
    const jaw = document.getElementById('jaw');
    jaw.addEventListener('input', () => page.setJaw(Number(jaw.value)));
    document.getElementById('settle').addEventListener('click', () => page.settle());
    document.getElementById('reset').addEventListener('click', () => {
      for (const name of names) { sliders[name].value = 0; page.setActivation(name, 0); }
      for (const { au } of actionUnits) setActionUnit(au, 0);
    });
    // Action units through the FACS map (assets/facs/au_map.json, packed into face.myoweb): the page's
    // C++ takes each AU to muscles, the jaw and the eyes by the path `myoshell drive` takes.
    const actionUnits = list(page.actionUnits()).map((s) => ({ au: Number(s.split(':')[0]), name: s.split(': ')[1] }));
    const auSliders = {};
    const auBox = document.getElementById('aus');
    for (const { au, name } of actionUnits)
      auSliders[au] = addSlider(auBox, `AU${au} ${name}`, (x) => page.setActionUnit(au, x));
    const setActionUnit = (au, x) => {
      call(() => page.setActionUnit(au, x));
      if (auSliders[au]) auSliders[au].value = x;
    };
    // A blink: AU45 (the palpebral orbicularis oculi) up and down over 0.3 s, a sine bump.
    let blinkStart = null;
    const blink = () => { blinkStart = performance.now(); };
    document.getElementById('blink').addEventListener('click', blink);
    // The takes (scenes' timelines packed into face.myoweb), played by the library's ScenePlayer.
    const takes = list(page.takeNames());
    const takeBox = document.getElementById('take');
    for (const name of takes) takeBox.appendChild(Object.assign(document.createElement('option'), { value: name, textContent: name }));
    let playStart = 0, playSpeed = 1, wasPlaying = false;
    const play = (name, speed = 1) => {
      const duration = call(() => page.play(name));
      playStart = performance.now();
      playSpeed = speed;
      wasPlaying = true;
      return duration;
    };
    // The sliders show what the take left when it ends or is stopped.
    const afterTake = () => {
      for (const name of names) sliders[name].value = page.activation(name);
      for (const { au } of actionUnits) auSliders[au].value = 0;
      jaw.value = page.jawOpen();
      pitch.value = 0;
      gravity.checked = true;
    };
    document.getElementById('play').addEventListener('click', () => play(takeBox.value));
    document.getElementById('stop').addEventListener('click', () => { page.stopPlaying(); });
    // The mouse: a drag that starts on the skin pulls it (Page::grab: a force at the vertex, projected
    // on the basis, that moves it by the mouse's motion in the screen's plane); elsewhere, or with
    // shift, it turns the view.
    const canvas = document.getElementById('canvas');
    let drag = null, pull = null;
    const grabInfo = document.getElementById('grabinfo');
    canvas.addEventListener('pointerdown', (e) => {
      canvas.setPointerCapture(e.pointerId);
      const r = canvas.getBoundingClientRect();
      const hit = e.shiftKey ? null : drawing.pick(e.clientX - r.left, e.clientY - r.top);
      const seconds = hit ? call(() => page.grab(hit.vertex)) : -1;
      if (seconds >= 0) {
        pull = { x: e.clientX, y: e.clientY, scale: hit.depth * drawing.pixelScale * devicePixelRatio };
        hook.grabSeconds = seconds;
        grabInfo.textContent = `grabbed vertex ${hit.vertex} in ${(seconds * 1000).toFixed(3)} ms`;
      } else {
        drag = [e.clientX, e.clientY];
      }
    });
    canvas.addEventListener('pointerup', () => {
      drag = null;
      if (pull) { page.release(); pull = null; }
    });
    canvas.addEventListener('pointermove', (e) => {
      if (pull) {
        const dx = (e.clientX - pull.x) * pull.scale, dy = -(e.clientY - pull.y) * pull.scale;
        const d = [0, 1, 2].map((c) => dx * drawing.right[c] + dy * drawing.up[c]);
        const f = call(() => page.moveGrab(d[0], d[1], d[2]));
        grabInfo.textContent = `pulling vertex ${page.grabbed()}: ${Math.hypot(...d).toFixed(2)} cm, |f| ${f.toFixed(0)} dyn`;
        return;
      }
      if (!drag) return;
      drawing.yaw += (e.clientX - drag[0]) * 0.01;
      drawing.pitch = Math.max(-1.2, Math.min(1.2, drawing.pitch + (e.clientY - drag[1]) * 0.01));
      drag = [e.clientX, e.clientY];
    });

    Object.assign(hook, {
      muscleNames: names,
      vertexCount: page.vertexCount(),
      modeCount: page.modeCount(),
      buildSeconds: page.buildSeconds(),
      setActivation(name, value) {
        call(() => page.setActivation(name, value));
        if (sliders[name]) sliders[name].value = value;
      },
      takes,
      actionUnits,
      setActionUnit,
      actionUnit(au) { return page.actionUnit(au); },
      activation(name) { return call(() => page.activation(name)); },  // slider + action units, clamped
      blink,
      // Plays a take from the neutral face (speed: take seconds per wall second); returns its duration (s).
      play(name, speed = 1) { return play(name, speed); },
      stop() { page.stopPlaying(); },
      // The mouse grab by hand: grab(i) returns its seconds (−1 for a vertex held fixed); move(δ) in cm.
      grab(i) { return (hook.grabSeconds = call(() => page.grab(i))); },
      moveGrab(dx, dy, dz) { return call(() => page.moveGrab(dx, dy, dz)); },
      release() { page.release(); },
      grabSeconds: 0,
      // Draws with the modes as morph targets on the GPU (true) or positions uploaded (false).
      gpuMorph(on) { gpu.checked = !!on; call(() => drawing.setGpuMorph(!!on)); },
      // The native renderer's front view on a size×size canvas (`myoshell render --view front`'s
      // camera), or the page's own view with 0.
      pictureView(size) {
        const rest = [];
        for (let i = 0; i < drawing.n; ++i) rest.push(...list(page.restVertex(i)));
        drawing.setPicture(size, list(page.frame()), rest);
        document.getElementById('stats').style.display = size ? 'none' : '';  // the picture alone
      },
      setGravity(on) { gravity.checked = !!on; call(() => page.setGravity(!!on)); },
      setJaw(deg) { jaw.value = deg; call(() => page.setJaw(deg)); },
      setHeadPitch(deg) { pitch.value = deg; call(() => page.setHeadPitch(deg)); },
      settle() { return call(() => page.settle()); },
      vertex(i) { return call(() => list(page.vertex(i))); },
      restVertex(i) { return call(() => list(page.restVertex(i))); },
      landmarkVertex(name) { return call(() => page.landmarkVertex(name)); },
      // Steps `count` times as fast as it can (the settled hold released): steps/s of the whole face.
      benchmark(count) {
        if (page.settled()) call(() => page.setGravity(gravity.checked));  // releases the hold
        const s = call(() => page.step(count, 0));
        return count / s;
      },
      stepsPerSecond: 0,
      framesPerSecond: 0,
    });

    // Read live (Object.assign would copy a getter's value once).
    Object.defineProperties(hook, {
      playing: { get: () => page.playing() },
      time: { get: () => page.time() },          // s, the player's clock
      duration: { get: () => page.duration() },  // s, the take playing or last played
    });

    // Real time: as many steps of dt as the wall clock advanced (at most 0.1 s of them a frame).
    const dt = page.dt();
    let last = performance.now(), owed = 0, frames = 0, steps = 0, stepSeconds = 0, windowStart = last;
    const stats = document.getElementById('stats');
    const playClock = document.getElementById('playclock');
    function frame(now) {
      owed = Math.min(owed + (now - last) / 1000, 0.1);
      last = now;
      const k = Math.floor(owed / dt);
      owed -= k * dt;
      if (blinkStart !== null) {
        const s = (now - blinkStart) / 300;
        if (s >= 1) blinkStart = null;
        setActionUnit(45, s >= 1 ? 0 : Math.sin(Math.PI * s));
      }
      try {
        if (page.playing()) {
          const before = page.stepCount();
          stepSeconds += page.step(0, ((now - playStart) / 1000) * playSpeed);
          steps += page.stepCount() - before;
          playClock.textContent = `${page.time().toFixed(2)} / ${page.duration().toFixed(2)} s`;
        } else if (k > 0 && !page.settled()) { stepSeconds += page.step(k, 0); steps += k; }
        if (wasPlaying && !page.playing()) { wasPlaying = false; afterTake(); playClock.textContent += ' (ended)'; }
      } catch (e) {
        hook.error = message(Module, e);
        status.textContent = hook.error;
      }
      drawing.draw();
      ++frames;
      if (now - windowStart > 1000) {
        const span = (now - windowStart) / 1000;
        hook.framesPerSecond = frames / span;
        if (stepSeconds > 0) hook.stepsPerSecond = steps / stepSeconds;
        stats.textContent =
          `${hook.framesPerSecond.toFixed(1)} frames/s\n` +
          `${steps} steps in ${span.toFixed(2)} s (${(steps / span).toFixed(0)}/s real time)\n` +
          `step capacity ${hook.stepsPerSecond.toFixed(0)} steps/s (dt ${(dt * 1000).toFixed(2)} ms)\n` +
          `${page.vertexCount()} vertices, ${page.modeCount()} modes, built in ${hook.buildSeconds.toFixed(2)} s`;
        frames = 0; steps = 0; stepSeconds = 0; windowStart = now;
      }
      requestAnimationFrame(frame);
    }
    requestAnimationFrame(frame);
    hook.loadSeconds = (performance.now() - pageStart) / 1000;
    hook.ready = true;
    status.textContent = `ready in ${hook.loadSeconds.toFixed(2)} s (face built in ${hook.buildSeconds.toFixed(2)} s)`;
  } catch (e) {
    hook.error = message(Module, e);
    status.textContent = 'error: ' + hook.error;
    console.error('myoshell: ' + hook.error);
  }
}

main();
