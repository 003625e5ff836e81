// skylight view (docs/VIEWER.md): the page's user interface and WebGL2 plumbing. It holds no model:
// every sky is the GLSL the library returns for it (SkylightWasm.sky: the model's own function and
// its set-up's uniforms), every direction the camera GLSL of render/glsl_camera.h, the CPU
// reference and the sun's position the library compiled to WebAssembly, the models' schemas and
// the false-colour scale what `skylight view` wrote into view_data.js.
'use strict';
(function () {
  const t0 = performance.now();
  const VIEW = window.SKYLIGHT_VIEW;
  const query = new URLSearchParams(location.search);
  const TEST = query.get('test') === '1';
  const $ = (id) => document.getElementById(id);
  const FRAME = { fisheye: [512, 512], equirect: [1024, 512], camera: [800, 500] };
  const TEST_FRAME = [1024, 512];  // the test contract's frame (equirect)
  const SUN_KEYS = ['sun-zenith', 'sun-azimuth'];

  let lib = null;  // the WebAssembly module
  let gl = null;
  const state = {
    a: { model: 'preetham', values: {} }, b: { model: 'hosek', values: {} },
    sunZenith: 45, sunAzimuth: 180, projection: 'fisheye', display: 'tonemap', exposure: 0,
    fcMin: 2, fcMax: 5, compare: 'none', split: 0.5, diffMax: 0.3,
    lookZenith: 75, lookAzimuth: 180, fov: 60, capture: -1,
  };

  // ---- models and their controls (from the schemas the library wrote) -------------------------
  const modelInfo = (name) => VIEW.models.find((m) => m.name === name);
  function gpuModels() {
    const inWasm = JSON.parse(lib.models());
    return VIEW.models.filter((m) => !m.no_gpu && inWasm.includes(m.name));
  }
  function controllable(p) {
    return !SUN_KEYS.includes(p.name) && p.kind !== 'text' || (p.choices && p.choices.length);
  }
  function defaultText(p) {
    if (p.default === null || p.default === 'required') return '';
    if (Array.isArray(p.default)) return p.default.join(',');
    return String(p.default);
  }
  function buildControls(side) {
    const box = $('params-' + side);
    box.innerHTML = '';
    const info = modelInfo(state[side].model);
    for (const p of info.parameters) {
      if (SUN_KEYS.includes(p.name)) continue;
      const label = document.createElement('label');
      const unit = p.unit && p.unit !== '1' ? ` [${p.unit}]` : '';
      label.title = p.description + (p.when_absent ? ` (absent: ${p.when_absent})` : '');
      label.append(`${p.name}${unit} `);
      if (!controllable(p) || p.kind === 'text' && !(p.choices && p.choices.length)) {
        label.className = 'disabled';
        label.append('(a file: not in the page)');
        box.append(label);
        continue;
      }
      const value = state[side].values[p.name] ?? (info.example[p.name] ?? defaultText(p));
      state[side].values[p.name] = value;
      const set = (v) => { state[side].values[p.name] = v; update(); };
      let input;
      if (p.choices && p.choices.length) {
        input = document.createElement('select');
        for (const c of p.choices) input.add(new Option(c, c));
        input.value = value;
        input.onchange = () => set(input.value);
        label.append(input);
      } else if (p.kind === 'flag') {
        input = document.createElement('input');
        input.type = 'checkbox';
        input.checked = value === 'true';
        input.onchange = () => set(input.checked ? 'true' : '');
        label.append(input);
      } else if (p.kind === 'numbers') {
        input = document.createElement('input');
        input.size = 28;
        input.value = value;
        input.placeholder = p.when_absent ? 'absent' : '';
        input.onchange = () => set(input.value.trim());
        label.append(input);
      } else {
        const row = document.createElement('span');
        row.className = 'row';
        input = document.createElement('input');
        input.type = 'number';
        input.step = p.kind === 'integer' ? '1' : 'any';
        input.min = p.min; input.max = p.max;
        input.value = value;
        input.placeholder = p.when_absent ? 'absent' : '';
        if (Number.isFinite(p.min) && Number.isFinite(p.max) && p.max - p.min <= 1000) {
          const range = document.createElement('input');
          range.type = 'range';
          range.min = p.min; range.max = p.max;
          range.step = p.kind === 'integer' ? '1' : String((p.max - p.min) / 500);
          range.value = value === '' ? p.min : value;
          range.oninput = () => { input.value = range.value; set(range.value); };
          input.onchange = () => { range.value = input.value; set(input.value.trim()); };
          row.append(range);
        } else {
          input.onchange = () => set(input.value.trim());
        }
        row.append(input);
        label.append(row);
      }
      box.append(label);
    }
  }
  // The model's parameters and the sun as the library's text form ("name=value" lines).
  function paramText(side) {
    const lines = [`sun-zenith=${state.sunZenith}`, `sun-azimuth=${state.sunAzimuth}`];
    for (const [k, v] of Object.entries(state[side].values)) if (v !== '') lines.push(`${k}=${v}`);
    return lines.join('\n');
  }

  // ---- GL -------------------------------------------------------------------------------------
  const HEADER = '#version 300 es\nprecision highp float;\nprecision highp int;\n';
  function compile(fragment) {
    const vs = gl.createShader(gl.VERTEX_SHADER);
    gl.shaderSource(vs, HEADER + 'void main() {\n  vec2 p = vec2(float((gl_VertexID << 1) & 2), ' +
      'float(gl_VertexID & 2));\n  gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n}\n');
    gl.compileShader(vs);
    const fs = gl.createShader(gl.FRAGMENT_SHADER);
    gl.shaderSource(fs, fragment);
    gl.compileShader(fs);
    if (!gl.getShaderParameter(fs, gl.COMPILE_STATUS))
      throw new Error('fragment shader does not compile: ' + gl.getShaderInfoLog(fs));
    const p = gl.createProgram();
    gl.attachShader(p, vs); gl.attachShader(p, fs);
    gl.linkProgram(p);
    if (!gl.getProgramParameter(p, gl.LINK_STATUS))
      throw new Error('program does not link: ' + gl.getProgramInfoLog(p));
    return p;
  }
  function setUniforms(p, uniforms) {
    gl.useProgram(p);
    for (const u of uniforms) {
      const loc = gl.getUniformLocation(p, u.name);
      if (loc === null) continue;  // removed by the compiler
      if (u.integer) gl.uniform1i(loc, u.values[0]);
      else [gl.uniform1f, gl.uniform2fv, gl.uniform3fv, gl.uniform4fv][u.values.length - 1]
        .call(gl, loc, u.values.length === 1 ? u.values[0] : u.values);
    }
  }
  function target(w, h) {
    const tex = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, tex);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA32F, w, h, 0, gl.RGBA, gl.FLOAT, null);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
    const fbo = gl.createFramebuffer();
    gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
    gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, tex, 0);
    if (gl.checkFramebufferStatus(gl.FRAMEBUFFER) !== gl.FRAMEBUFFER_COMPLETE)
      throw new Error('no float render target (EXT_color_buffer_float)');
    return { tex, fbo, w, h };
  }
  function draw(program, t) {
    gl.bindFramebuffer(gl.FRAMEBUFFER, t ? t.fbo : null);
    gl.viewport(0, 0, t ? t.w : gl.canvas.width, t ? t.h : gl.canvas.height);
    gl.useProgram(program);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
  }
  function readback(t) {
    const out = new Float32Array(t.w * t.h * 4);
    gl.bindFramebuffer(gl.FRAMEBUFFER, t.fbo);
    gl.readPixels(0, 0, t.w, t.h, gl.RGBA, gl.FLOAT, out);
    return out;  // GL rows: row 0 at the bottom
  }
  // Index of image pixel (col, row; row 0 at the top) in a readback.
  const at = (t, col, row) => ((t.h - 1 - row) * t.w + col) * 4;

  const PIXEL = '  vec2 pixel = vec2(gl_FragCoord.x, skylight_size.y - gl_FragCoord.y);\n' +
    '  vec3 dir;\n  bool valid = skylight_pixel_direction(pixel, dir);\n';
  // The sky pass: XYZ (Y in cd/m^2) of the model, alpha 1 where the camera has a direction.
  function skyProgram(sky, camera) {
    return compile(HEADER + sky.glsl + camera.glsl + 'out vec4 o;\nvoid main() {\n' + PIXEL +
      '  o = valid ? vec4(skylight_sky_xyz(dir), 1.0) : vec4(0.0);\n}\n');
  }
  // The directions pass: the camera's direction of every pixel (for the samples, the CPU check
  // and the sun drag).
  const directionPrograms = new Map();  // camera GLSL -> program
  function directionProgram(camera) {
    if (directionPrograms.has(camera.glsl)) return directionPrograms.get(camera.glsl);
    directionPrograms.set(camera.glsl, compileDirections(camera));
    return directionPrograms.get(camera.glsl);
  }
  function compileDirections(camera) {
    return compile(HEADER + lib.helpers() + camera.glsl + 'out vec4 o;\nvoid main() {\n' + PIXEL +
      '  o = vec4(dir, valid ? 1.0 : 0.0);\n}\n');
  }
  let displayProgram = null, palette = null;
  function makeDisplay() {
    displayProgram = compile(HEADER + lib.helpers() + `
uniform sampler2D u_a, u_b, u_palette;
uniform int u_mode;      // 0 tone mapped, 1 false colour, 2 difference
uniform int u_source;    // 0 A, 1 B, 2 split at u_split
uniform vec2 u_offset;   // the viewport's origin [px]
uniform float u_split, u_scale, u_fc_min, u_fc_max, u_diff_max, u_height;
out vec4 o;
float oetf(float c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055; }
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy - u_offset);
  vec4 a = texelFetch(u_a, p, 0), b = texelFetch(u_b, p, 0);
  int source = u_source;
  if (source == 2) source = float(p.x) < u_split ? 0 : 1;
  vec4 c = source == 0 ? a : b;
  if (c.w == 0.0) { o = vec4(0.12, 0.12, 0.13, 1.0); return; }
  if (u_mode == 2) {
    if (!(a.y > 0.0 && b.y > 0.0)) { o = vec4(0.12, 0.12, 0.13, 1.0); return; }  // no sky
    float d = log(b.y / a.y) / log(10.0);
    float t = clamp(d / u_diff_max, -1.0, 1.0);
    vec3 col = t < 0.0 ? mix(vec3(1.0), vec3(0.17, 0.4, 0.85), -t)
                       : mix(vec3(1.0), vec3(0.85, 0.2, 0.15), t);
    o = vec4(col, 1.0);
    return;
  }
  if (u_mode == 1) {
    float l = c.y > 0.0 ? log(c.y) / log(10.0) : u_fc_min;
    float t = clamp((l - u_fc_min) / (u_fc_max - u_fc_min), 0.0, 1.0);
    o = vec4(texture(u_palette, vec2(t, 0.5)).rgb, 1.0);
    return;
  }
  // The report's operator (render/tonemap.h): exposure, Reinhard L / (1 + L) on the luminance
  // with the colour's ratios kept, the sRGB OETF.
  vec3 rgb = max(skylight_xyz_to_srgb(c.xyz * u_scale), vec3(0.0));
  float l = c.y * u_scale;
  rgb *= l > 0.0 ? 1.0 / (1.0 + l) : 0.0;
  o = vec4(oetf(min(rgb.r, 1.0)), oetf(min(rgb.g, 1.0)), oetf(min(rgb.b, 1.0)), 1.0);
}
`);
    const fc = VIEW.false_colour.colours;
    const bytes = new Uint8Array(fc.length * 4);
    fc.forEach((c, i) => bytes.set([c[0], c[1], c[2], 255], 4 * i));
    palette = gl.createTexture();
    gl.bindTexture(gl.TEXTURE_2D, palette);
    gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, fc.length, 1, 0, gl.RGBA, gl.UNSIGNED_BYTE, bytes);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
    gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
  }

  // ---- a frame --------------------------------------------------------------------------------
  const programs = new Map();  // GLSL source -> program (a model's shader compiles once)
  function cachedSkyProgram(sky, camera) {
    const key = sky.glsl + camera.glsl;
    if (!programs.has(key)) programs.set(key, skyProgram(sky, camera));
    return programs.get(key);
  }
  // Renders model `side` into a float target of the camera: {target, sky, pixels} or {error}.
  // A model's tables (GpuSky::Table: row 0 first, as GL's row 0) as float textures read by
  // texelFetch, on the units after 0.
  const tableTextures = [];
  function bindTables(p, tables) {
    tables.forEach((t, k) => {
      if (!tableTextures[k]) tableTextures[k] = gl.createTexture();
      gl.activeTexture(gl.TEXTURE1 + k);
      gl.bindTexture(gl.TEXTURE_2D, tableTextures[k]);
      const [internal, format] = t.channels === 4 ? [gl.RGBA32F, gl.RGBA] : [gl.RGB32F, gl.RGB];
      gl.pixelStorei(gl.UNPACK_ALIGNMENT, 1);
      gl.texImage2D(gl.TEXTURE_2D, 0, internal, t.width, t.height, 0, format, gl.FLOAT,
                    new Float32Array(t.data));
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
      gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
      gl.useProgram(p);
      gl.uniform1i(gl.getUniformLocation(p, t.name), 1 + k);
    });
    gl.activeTexture(gl.TEXTURE0);
  }
  function renderSide(side, camera, w, h, t) {
    const sky = JSON.parse(lib.sky(state[side].model, paramText(side)));
    if (sky.error) return { error: sky.error };
    const p = cachedSkyProgram(sky, camera);
    setUniforms(p, camera.uniforms);
    setUniforms(p, sky.uniforms);
    bindTables(p, sky.tables);
    draw(p, t);
    return { target: t, sky, pixels: readback(t) };
  }
  function cameraOf(projection, w, h) {
    const c = JSON.parse(lib.camera(projection, w, h, state.lookZenith, state.lookAzimuth,
                                    state.fov));
    if (c.error) throw new Error(c.error);
    return c;
  }
  const targets = {};
  function targetsFor(w, h) {
    const key = w + 'x' + h;
    if (!targets[key]) targets[key] = { a: target(w, h), b: target(w, h), d: target(w, h) };
    return targets[key];
  }
  function percentile(values, q) {
    if (!values.length) return 0;
    const s = Float64Array.from(values).sort();
    return s[Math.min(s.length - 1, Math.floor(q * (s.length - 1) + 0.5))];
  }
  function luminances(r) {
    const out = [];
    for (let i = 0; i < r.pixels.length; i += 4) if (r.pixels[i + 3] > 0) out.push(r.pixels[i + 1]);
    return out;
  }

  let frame = null;  // the last frame: {w, h, camera, a, b, dirs}
  // A model whose set-up takes seconds (ModelInfo::costly_setup: tables per atmosphere and sun,
  // computed by the WebAssembly on one thread) is drawn after the page has said so.
  let pending = false, again = false;
  function update() {
    if (!lib) return;
    if (pending) { again = true; return; }  // drawn with the latest state once this one is done
    const costly = [state.a.model, state.compare !== 'none' ? state.b.model : null]
      .filter((m) => m && modelInfo(m).costly_setup);
    if (!costly.length) { render(); return; }
    pending = true;
    $('status').textContent = `computing ${costly.join(' and ')}'s tables in the page ` +
      '(bruneton: 20–40 s the first time, under a second per new sun)…';
    setTimeout(() => {
      pending = false;
      const t = performance.now();
      render();
      $('status').textContent = `drawn in ${fmt((performance.now() - t) / 1000, 2)} s`;
      if (again) { again = false; update(); }
    }, 30);
  }
  function render() {
    const [w, h] = FRAME[state.projection];
    let camera;
    try { camera = cameraOf(state.projection, w, h); } catch (e) { $('status').textContent = e.message; return; }
    const t = targetsFor(w, h);
    const a = renderSide('a', camera, w, h, t.a);
    $('error-a').textContent = a.error || '';
    const compare = state.compare !== 'none';
    const b = compare ? renderSide('b', camera, w, h, t.b) : null;
    $('error-b').textContent = b && b.error ? b.error : '';
    if (a.error || (b && b.error)) return;  // the last good frame stays
    const dp = directionProgram(camera);
    setUniforms(dp, camera.uniforms);
    draw(dp, t.d);
    // The tone mapping's white: the frame's 99th percentile of luminance (exposure 0 EV).
    frame = { w, h, camera, a, b, dirs: readback(t.d), white: percentile(luminances(a), 0.99) || 1 };
    present();
    describe();
    permalink();
  }
  function present() {
    const { w, h, a, b } = frame;
    const side = state.compare === 'side';
    const canvas = gl.canvas;
    if (canvas.width !== (side ? 2 * w : w) || canvas.height !== h) {
      canvas.width = side ? 2 * w : w; canvas.height = h;
      $('overlay').width = canvas.width; $('overlay').height = h;
    }
    const p = displayProgram;
    gl.useProgram(p);
    gl.uniform1f(gl.getUniformLocation(p, 'u_scale'), Math.pow(2, state.exposure) / frame.white);
    gl.uniform1f(gl.getUniformLocation(p, 'u_fc_min'), state.fcMin);
    gl.uniform1f(gl.getUniformLocation(p, 'u_fc_max'), state.fcMax);
    gl.uniform1f(gl.getUniformLocation(p, 'u_diff_max'), state.diffMax);
    gl.uniform1f(gl.getUniformLocation(p, 'u_split'), state.split * w);
    const mode = state.compare === 'difference' ? 2 : state.display === 'falsecolour' ? 1 : 0;
    gl.uniform1i(gl.getUniformLocation(p, 'u_mode'), mode);
    gl.activeTexture(gl.TEXTURE0); gl.bindTexture(gl.TEXTURE_2D, a.target.tex);
    gl.activeTexture(gl.TEXTURE1); gl.bindTexture(gl.TEXTURE_2D, (b || a).target.tex);
    gl.activeTexture(gl.TEXTURE2); gl.bindTexture(gl.TEXTURE_2D, palette);
    gl.uniform1i(gl.getUniformLocation(p, 'u_a'), 0);
    gl.uniform1i(gl.getUniformLocation(p, 'u_b'), 1);
    gl.uniform1i(gl.getUniformLocation(p, 'u_palette'), 2);
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    const halves = side ? [[0, 0], [w, 1]] : [[0, state.compare === 'split' ? 2 : 0]];
    for (const [x, source] of halves) {
      gl.viewport(x, 0, w, h);
      gl.uniform2f(gl.getUniformLocation(p, 'u_offset'), x, 0);
      gl.uniform1i(gl.getUniformLocation(p, 'u_source'), source);
      gl.drawArrays(gl.TRIANGLES, 0, 3);
    }
    drawOverlay();
    drawLegend(mode);
  }

  // ---- what the page says about the frame -----------------------------------------------------
  const fmt = (x, d = 3) => Number(x).toPrecision(d);
  function describe() {
    const { a, b } = frame;
    const issues = a.sky.issues.map((i) => `${i.validity}: ${i.message}`);
    $('domain').textContent = `${state.a.model}: ${a.sky.comment} — domain ${a.sky.validity}` +
      (issues.length ? ' (' + issues.join('; ') + ')' : '');
    $('glsl').textContent = a.sky.glsl;
    if (b) {
      const d = [];
      for (let i = 0; i < a.pixels.length; i += 4) {
        const ya = a.pixels[i + 1], yb = b.pixels[i + 1];
        if (a.pixels[i + 3] > 0 && ya > 0 && yb > 0) d.push(Math.abs(Math.log10(yb / ya)));
      }
      $('diff-stats').textContent = `|log10(${state.b.model} / ${state.a.model})| over the frame: ` +
        `median ${fmt(percentile(d, 0.5))} (${fmt(100 * (Math.pow(10, percentile(d, 0.5)) - 1))} %), ` +
        `p95 ${fmt(percentile(d, 0.95))} (${fmt(100 * (Math.pow(10, percentile(d, 0.95)) - 1))} %)`;
    } else {
      $('diff-stats').textContent = '';
    }
    $('check-result').textContent = '';
  }
  function drawLegend(mode) {
    const c = $('legend'), g = c.getContext('2d');
    c.width = gl.canvas.width;
    g.clearRect(0, 0, c.width, c.height);
    g.fillStyle = '#ddd';
    g.font = '11px sans-serif';
    if (mode === 0) { g.fillText('tone mapped: 99th percentile of luminance at exposure 0 EV', 4, 14); return; }
    const n = 256, w = Math.min(c.width - 8, 512);
    for (let i = 0; i < n; ++i) {
      const t = i / (n - 1);
      if (mode === 1) {
        const col = VIEW.false_colour.colours[i];
        g.fillStyle = `rgb(${col[0]},${col[1]},${col[2]})`;
      } else {
        const s = 2 * t - 1, m = Math.abs(s);
        const to = s < 0 ? [43, 102, 217] : [217, 51, 38];
        g.fillStyle = `rgb(${(255 + (to[0] - 255) * m) | 0},${(255 + (to[1] - 255) * m) | 0},${(255 + (to[2] - 255) * m) | 0})`;
      }
      g.fillRect(4 + (w * i) / n, 0, w / n + 1, 16);
    }
    g.fillStyle = '#ddd';
    const lo = mode === 1 ? state.fcMin : -state.diffMax, hi = mode === 1 ? state.fcMax : state.diffMax;
    for (let k = 0; k <= 4; ++k) {
      const v = lo + ((hi - lo) * k) / 4;
      g.fillText(mode === 1 ? `10^${fmt(v, 2)}` : `${fmt(v, 2)}`, 4 + (w * k) / 4 - (k === 4 ? 30 : 0), 30);
    }
    g.fillText(mode === 1 ? 'luminance [cd/m²]' : `log10(${state.b.model} / ${state.a.model})`, 4, 44);
  }
  // The sun and the measured samples over the sky (fisheye and equirect: Camera::pixel).
  function drawOverlay() {
    const c = $('overlay'), g = c.getContext('2d');
    g.clearRect(0, 0, c.width, c.height);
    if (state.projection === 'camera') return;
    const { w, h } = frame;
    const copies = state.compare === 'side' ? [0, w] : [0];
    const pts = [state.sunZenith, state.sunAzimuth];
    const cap = state.capture >= 0 && VIEW.measured ? VIEW.measured.captures[state.capture] : null;
    if (cap) for (const s of cap.samples) pts.push(s[0], s[1]);
    const px = lib.project(state.projection, w, h, pts);
    for (const x0 of copies) {
      g.strokeStyle = '#ffe000'; g.lineWidth = 2;
      if (Number.isFinite(px[0])) { g.beginPath(); g.arc(x0 + px[0], px[1], 7, 0, 2 * Math.PI); g.stroke(); }
      if (!cap) continue;
      cap.samples.forEach((s, i) => {
        const x = px[2 + 2 * i], y = px[3 + 2 * i];
        if (!Number.isFinite(x)) return;
        const t = Math.min(1, Math.max(0, (Math.log10(s[2]) - state.fcMin) / (state.fcMax - state.fcMin)));
        const col = VIEW.false_colour.colours[Math.round(t * 255)];
        g.fillStyle = `rgb(${col[0]},${col[1]},${col[2]})`;
        g.strokeStyle = '#000'; g.lineWidth = 1;
        g.beginPath(); g.arc(x0 + x, y, 4, 0, 2 * Math.PI); g.fill(); g.stroke();
      });
    }
  }

  // ---- GPU = CPU: the frame by the library in the page ----------------------------------------
  function check() {
    const { w, h, a, dirs } = frame;
    const xyz = [], gpu = [];
    for (let row = 0; row < h; ++row) for (let col = 0; col < w; ++col) {
      const i = at(frame.a.target, col, row);
      if (dirs[i + 3] === 0) continue;
      xyz.push(dirs[i], dirs[i + 1], dirs[i + 2]);
      gpu.push(a.pixels[i + 1]);
    }
    const t = performance.now();
    const cpu = lib.luminance(state.a.model, paramText('a'), xyz);
    const seconds = (performance.now() - t) / 1000;
    let peak = 0;
    for (const v of cpu) peak = Math.max(peak, v);
    const rel = [];
    let worst = 0, worstAt = -1;
    cpu.forEach((v, i) => {
      if (!(v > 1e-3 * peak)) return;
      const r = Math.abs(gpu[i] - v) / v;
      rel.push(r);
      if (r > worst) { worst = r; worstAt = i; }
    });
    const dirOf = (i) => {
      const z = xyz[3 * i + 2], az = Math.atan2(xyz[3 * i], xyz[3 * i + 1]) * 180 / Math.PI;
      const zen = Math.atan2(Math.hypot(xyz[3 * i], xyz[3 * i + 1]), z) * 180 / Math.PI;
      return `zenith ${fmt(zen, 4)}°, azimuth ${fmt((az + 360) % 360, 4)}°`;
    };
    $('check-result').textContent = `${rel.length} pixels by the library (double) in ${fmt(seconds, 2)} s: ` +
      `relative difference median ${fmt(percentile(rel, 0.5), 2)}, p99 ${fmt(percentile(rel, 0.99), 2)}, ` +
      `largest ${fmt(worst, 2)}` + (worstAt >= 0 ? ` at ${dirOf(worstAt)}` : '');
  }

  // ---- the view as a link ---------------------------------------------------------------------
  function permalink() {
    const q = new URLSearchParams();
    q.set('model', state.a.model);
    for (const [k, v] of Object.entries(state.a.values)) if (v !== '') q.set(k, v);
    q.set('sun_zenith', state.sunZenith); q.set('sun_azimuth', state.sunAzimuth);
    for (const k of ['projection', 'display', 'exposure', 'compare', 'split', 'capture'])
      q.set(k, state[k]);
    q.set('look', `${state.lookZenith},${state.lookAzimuth},${state.fov}`);
    if (state.compare !== 'none') {
      q.set('model_b', state.b.model);
      for (const [k, v] of Object.entries(state.b.values)) if (v !== '') q.set('b.' + k, v);
    }
    $('permalink').href = '?' + q.toString();
  }
  function restore() {
    const g = (k) => query.get(k);
    if (g('model')) state.a.model = g('model');
    if (g('model_b')) state.b.model = g('model_b');
    const num = (k, d) => (g(k) !== null && g(k) !== '' && Number.isFinite(+g(k)) ? +g(k) : d);
    state.sunZenith = num('sun_zenith', state.sunZenith);
    state.sunAzimuth = num('sun_azimuth', state.sunAzimuth);
    for (const k of ['projection', 'display', 'compare']) if (g(k)) state[k] = g(k);
    state.exposure = num('exposure', 0); state.split = num('split', 0.5);
    state.capture = num('capture', -1);
    if (g('look')) [state.lookZenith, state.lookAzimuth, state.fov] = g('look').split(',').map(Number);
    const reserved = new Set(['model', 'model_b', 'test', 'sun_zenith', 'sun_azimuth', 'projection',
      'display', 'exposure', 'compare', 'split', 'capture', 'look']);
    for (const [k, v] of query) {
      if (reserved.has(k)) continue;
      if (k.startsWith('b.')) state.b.values[k.slice(2).replace(/_/g, '-')] = v;
      else state.a.values[k.replace(/_/g, '-')] = v;
    }
  }

  // ---- the test contract: ?test=1&model=M&<param>=<value>...&sun_zenith=Z&sun_azimuth=A ---------
  function runTest() {
    const result = {};
    try {
      state.projection = 'equirect';
      const [w, h] = TEST_FRAME;
      const camera = cameraOf('equirect', w, h);
      const t = targetsFor(w, h);
      const a = renderSide('a', camera, w, h, t.a);
      if (a.error) throw new Error(a.error);
      const dp = directionProgram(camera);
      setUniforms(dp, camera.uniforms);
      draw(dp, t.d);
      const dirs = readback(t.d);
      // Frames per second: frames of the sky pass, each finished by a one-pixel readback.
      const p = cachedSkyProgram(a.sky, camera), one = new Float32Array(4);
      const frames = 10, start = performance.now();
      for (let i = 0; i < frames; ++i) {
        draw(p, t.a);
        gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, one);
      }
      const ms = (performance.now() - start) / frames;
      // Pixel centres every 16th column and 8th row of the upper half: 64 x 32 = 2048 samples.
      const samples = [], xyz = [];
      for (let row = 4; row < h / 2; row += 8) for (let col = 8; col < w; col += 16) {
        const i = at(t.a, col, row);
        if (dirs[i + 3] === 0 || dirs[i + 2] <= 0) continue;
        const [x, y, z] = [dirs[i], dirs[i + 1], dirs[i + 2]];
        samples.push({ zenith_deg: Math.atan2(Math.hypot(x, y), z) * 180 / Math.PI,
                       azimuth_deg: ((Math.atan2(x, y) * 180 / Math.PI) + 360) % 360,
                       luminance: a.pixels[i + 1] });
        xyz.push(x, y, z);
      }
      const cpu = lib.luminance(state.a.model, paramText('a'), xyz);
      samples.forEach((s, k) => { s.library_luminance = cpu[k]; });
      const dbg = gl.getExtension('WEBGL_debug_renderer_info');
      Object.assign(result, {
        model: state.a.model, parameters: a.sky.parameters, comment: a.sky.comment,
        sun_zenith_deg: state.sunZenith, sun_azimuth_deg: state.sunAzimuth, width: w, height: h,
        renderer: dbg ? gl.getParameter(dbg.UNMASKED_RENDERER_WEBGL) : gl.getParameter(gl.RENDERER),
        fps: 1000 / ms, frame_ms: ms, load_ms: performance.now() - t0, samples });
    } catch (e) {
      result.error = String(e.message || e);
    }
    const pre = $('test-result');
    pre.textContent = JSON.stringify(result);
    pre.hidden = false;
  }

  // ---- wiring -----------------------------------------------------------------------------------
  function fillModelLists() {
    const models = gpuModels();
    for (const side of ['a', 'b']) {
      const sel = $('model-' + side);
      for (const m of models) sel.add(new Option(m.name, m.name));
      if (!models.some((m) => m.name === state[side].model)) state[side].model = models[0].name;
      sel.value = state[side].model;
      sel.onchange = () => { state[side].model = sel.value; state[side].values = {}; buildControls(side); update(); };
      buildControls(side);
    }
    const inWasm = JSON.parse(lib.models());
    $('no-gpu').innerHTML = '';
    for (const m of VIEW.models) {
      if (models.includes(m)) continue;
      const why = m.no_gpu || 'its set-up is not in the page\'s WebAssembly build';
      const d = document.createElement('div');
      d.textContent = `${m.name}: ${why}`;
      $('no-gpu').append(d);
      void inWasm;
    }
  }
  function bindSun() {
    const pairs = [['sun-zenith', 'sunZenith'], ['sun-azimuth', 'sunAzimuth']];
    for (const [id, key] of pairs) {
      const n = $(id), r = $(id + '-range');
      n.value = state[key]; r.value = ((state[key] % 360) + 360) % 360;
      n.onchange = () => { state[key] = +n.value; r.value = n.value; update(); };
      r.oninput = () => { state[key] = +r.value; n.value = r.value; update(); };
    }
  }
  function setSun(z, a) {
    state.sunZenith = +z.toFixed(2); state.sunAzimuth = +(((a % 360) + 360) % 360).toFixed(2);
    bindSun();
    update();
  }
  function wire() {
    bindSun();
    const simple = [['projection', 'projection', String], ['display', 'display', String],
      ['compare', 'compare', String], ['fc-min', 'fcMin', Number], ['fc-max', 'fcMax', Number],
      ['diff-max', 'diffMax', Number]];
    for (const [id, key, conv] of simple) {
      $(id).value = state[key];
      $(id).onchange = () => { state[key] = conv($(id).value); update(); };
    }
    $('exposure').value = state.exposure;
    $('exposure').oninput = () => {
      state.exposure = +$('exposure').value; $('exposure-value').textContent = state.exposure;
      if (frame) present();
    };
    $('sun-from-time').onclick = () => {
      const r = JSON.parse(lib.sunPosition(`time=${$('time').value}\nlat=${$('lat').value}\nlon=${$('lon').value}`));
      $('error-sun').textContent = r.error || '';
      if (!r.error) setSun(r.zenith_deg, r.azimuth_deg);
    };
    $('check').onclick = () => { if (frame) check(); };
    if (VIEW.measured) {
      VIEW.measured.captures.forEach((c, i) => $('capture').add(new Option(c.name, String(i))));
      $('measured-source').textContent = `${VIEW.measured.captures.length} captures from ${VIEW.measured.source}; ` +
        'points coloured on the false-colour scale by their measured luminance';
    } else {
      $('measured-source').textContent = 'no measured captures in this page';
    }
    $('capture').value = String(state.capture);
    $('capture').onchange = () => { state.capture = +$('capture').value; if (frame) drawOverlay(); permalink(); };
    $('capture-sun').onclick = () => {
      const c = VIEW.measured && VIEW.measured.captures[state.capture];
      if (c) setSun(c.sun_zenith_deg, c.sun_azimuth_deg);
    };
    // Dragging: the sun on the dome; the look direction in perspective; the split line.
    const canvas = $('sky');
    let dragging = false, last = null;
    const pointer = (e) => {
      const r = canvas.getBoundingClientRect();
      return [(e.clientX - r.left) * canvas.width / r.width, (e.clientY - r.top) * canvas.height / r.height];
    };
    const act = (e) => {
      const [x, y] = pointer(e);
      if (state.compare === 'split' && Math.abs(x - state.split * frame.w) < 12 && !e.shiftKey) {
        state.split = Math.min(1, Math.max(0, x / frame.w)); present(); permalink(); return;
      }
      if (state.projection === 'camera' && !e.shiftKey) {
        if (last) {
          state.lookAzimuth = (state.lookAzimuth - (x - last[0]) * 0.2 + 360) % 360;
          state.lookZenith = Math.min(179, Math.max(1, state.lookZenith - (y - last[1]) * 0.2));
          update();
        }
        last = [x, y];
        return;
      }
      const col = Math.floor(x % frame.w), row = Math.floor(y);
      if (row < 0 || row >= frame.h) return;
      const i = at(frame.a.target, col, row);
      if (frame.dirs[i + 3] === 0) return;
      const [dx, dy, dz] = [frame.dirs[i], frame.dirs[i + 1], frame.dirs[i + 2]];
      setSun(Math.atan2(Math.hypot(dx, dy), dz) * 180 / Math.PI, Math.atan2(dx, dy) * 180 / Math.PI);
    };
    canvas.onmousedown = (e) => { dragging = true; last = null; act(e); };
    window.onmouseup = () => { dragging = false; last = null; };
    canvas.onmousemove = (e) => { if (dragging) act(e); };
    canvas.onwheel = (e) => {
      if (state.projection !== 'camera') return;
      e.preventDefault();
      state.fov = Math.min(150, Math.max(5, state.fov * Math.exp(e.deltaY * 0.001)));
      update();
    };
  }

  function start() {
    $('software').textContent = `${VIEW.software}; models: the library's GLSL, set-up by its WebAssembly`;
    gl = $('sky').getContext('webgl2', { antialias: false, preserveDrawingBuffer: true });
    if (!gl) { $('status').textContent = 'This browser has no WebGL2.'; return; }
    if (!gl.getExtension('EXT_color_buffer_float')) {
      $('status').textContent = 'This browser cannot render into float targets (EXT_color_buffer_float).';
      return;
    }
    SkylightWasm().then((m) => {
      lib = m;
      restore();
      if (TEST) { runTest(); return; }
      makeDisplay();
      fillModelLists();
      wire();
      update();
      $('status').textContent = `ready in ${fmt((performance.now() - t0) / 1000, 2)} s`;
    }).catch((e) => { $('status').textContent = 'the library did not load: ' + e; });
  }
  start();
})();
