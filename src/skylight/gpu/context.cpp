#include "skylight/gpu/context.h"

// EGL and GL 3.3 core, linked directly (libEGL + libOpenGL of GLVND export every GL 3.3 entry
// point): no loader library.
#define EGL_EGLEXT_PROTOTYPES
#define GL_GLEXT_PROTOTYPES
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <GL/glcorearb.h>
#include <fmt/format.h>

#include <dlfcn.h>
#include <link.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <string>
#include <vector>

namespace skylight::gpu {

namespace {

[[noreturn]] void fail(const std::string& what) {
  throw GpuError("gpu: " + what);
}

std::string egl_error_text(EGLint e) {
  return fmt::format("EGL error 0x{:04x}", e);
}

void check_gl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) fail(fmt::format("{} failed (GL error 0x{:04x})", what, e));
}

bool has_extension(const char* list, std::string_view name) {
  if (list == nullptr) return false;
  std::string_view all(list);
  std::size_t pos = 0;
  while (pos < all.size()) {
    const std::size_t end = std::min(all.find(' ', pos), all.size());
    if (all.substr(pos, end - pos) == name) return true;
    pos = end + 1;
  }
  return false;
}

// Marks every shared object loaded now as never to be unloaded (RTLD_NODELETE). EGL loads Mesa's
// driver (and LLVM) with dlopen and unloads it at exit, after the driver's code may have run on
// the calling thread (vertex processing runs there): its dynamic TLS block then dangles, and
// LeakSanitizer's exit-time scan of thread-local storage crashes on it. Objects that stay loaded
// until the process ends are what a process that keeps its GL display does anyway.
void pin_loaded_libraries() {
  std::vector<std::string> names;
  dl_iterate_phdr(
      [](dl_phdr_info* info, std::size_t, void* out) {
        if (info->dlpi_name != nullptr && info->dlpi_name[0] != '\0')
          static_cast<std::vector<std::string>*>(out)->emplace_back(info->dlpi_name);
        return 0;
      },
      &names);
  for (const std::string& name : names)
    // RTLD_NOLOAD: only a handle to an object already there (its count drops again below).
    if (void* h = dlopen(name.c_str(), RTLD_LAZY | RTLD_NOLOAD | RTLD_NODELETE)) dlclose(h);
}

}  // namespace

const std::string_view kFullscreenVertexShader =
    "#version 330 core\n"
    "// Two triangles covering clip space [-1, 1]^2.\n"
    "const vec2 kCorners[6] = vec2[6](vec2(-1.0, -1.0), vec2(1.0, -1.0), vec2(1.0, 1.0),\n"
    "                                 vec2(-1.0, -1.0), vec2(1.0, 1.0), vec2(-1.0, 1.0));\n"
    "void main() { gl_Position = vec4(kCorners[gl_VertexID], 0.0, 1.0); }\n";

// ---- context ------------------------------------------------------------------------------------

struct Context::Impl {
  EGLDisplay display = EGL_NO_DISPLAY;
  EGLContext context = EGL_NO_CONTEXT;
  GLuint vao = 0;
};

namespace {

// The surfaceless display, initialised once per process and never terminated: eglTerminate
// unloads Mesa's driver, which leaves some of its allocations unreachable (LeakSanitizer reports
// 112 bytes from an unloaded module), and re-initialising costs the driver load for every Context.
EGLDisplay surfaceless_display() {
  static std::mutex mutex;
  static EGLDisplay display = EGL_NO_DISPLAY;
  const std::lock_guard lock(mutex);
  if (display != EGL_NO_DISPLAY) return display;
  const char* client_ext = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  if (!has_extension(client_ext, "EGL_MESA_platform_surfaceless"))
    fail(
        "no EGL surfaceless platform (EGL_MESA_platform_surfaceless): install libegl-mesa0 and "
        "libgl1-mesa-dri (scripts/setup.sh)");
  auto get_platform_display = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  if (get_platform_display == nullptr) fail("EGL has no eglGetPlatformDisplayEXT");
  const EGLDisplay d =
      get_platform_display(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
  EGLint major = 0, minor = 0;
  if (d == EGL_NO_DISPLAY || !eglInitialize(d, &major, &minor))
    fail("cannot initialise the EGL surfaceless display (" + egl_error_text(eglGetError()) +
         "): is libgl1-mesa-dri installed?");
  pin_loaded_libraries();
  display = d;
  return display;
}

}  // namespace

Context::Context() : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.display = surfaceless_display();
  if (!eglBindAPI(EGL_OPENGL_API))
    fail("EGL cannot bind the desktop OpenGL API (" + egl_error_text(eglGetError()) + ")");
  const EGLint config_attribs[] = {EGL_SURFACE_TYPE, EGL_PBUFFER_BIT, EGL_RENDERABLE_TYPE,
                                   EGL_OPENGL_BIT, EGL_NONE};
  EGLConfig config = nullptr;
  EGLint configs = 0;
  const bool have_config =
      eglChooseConfig(m.display, config_attribs, &config, 1, &configs) && configs > 0;
  const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                    3,
                                    EGL_CONTEXT_MINOR_VERSION,
                                    3,
                                    EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                    EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                    EGL_NONE};
  // Surfaceless: no config is needed when EGL_KHR_no_config_context is there.
  m.context = eglCreateContext(m.display, have_config ? config : EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT,
                               context_attribs);
  if (m.context == EGL_NO_CONTEXT) {
    const EGLint e = eglGetError();
    fail("cannot create an OpenGL 3.3 core context (" + egl_error_text(e) + ")");
  }
  if (!eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, m.context)) {
    const EGLint e = eglGetError();
    eglDestroyContext(m.display, m.context);
    fail("cannot make the OpenGL context current without a surface (" + egl_error_text(e) + ")");
  }
  // The driver may load more at the first context (surfaceless_display pins what it loaded).
  static std::once_flag pinned;
  std::call_once(pinned, pin_loaded_libraries);
  // Core profile draws need a vertex array object, even without attributes.
  glGenVertexArrays(1, &m.vao);
  glBindVertexArray(m.vao);
  check_gl("creating the vertex array");
}

Context::~Context() {
  Impl& m = *impl_;
  glDeleteVertexArrays(1, &m.vao);
  eglMakeCurrent(m.display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(m.display, m.context);
  eglReleaseThread();  // the display stays initialised (surfaceless_display)
}

std::string Context::renderer() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  return s ? s : "";
}

std::string Context::version() const {
  const auto* s = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  return s ? s : "";
}

void Context::finish() const {
  glFinish();
}

// ---- textures -----------------------------------------------------------------------------------

Texture::Texture(const io::ImageF& image) : width_(image.width), height_(image.height) {
  static constexpr GLint kInternal[] = {GL_R32F, GL_RG32F, GL_RGB32F, GL_RGBA32F};
  static constexpr GLenum kFormat[] = {GL_RED, GL_RG, GL_RGB, GL_RGBA};
  if (image.channels < 1 || image.channels > 4 || image.width < 1 || image.height < 1 ||
      image.data.size() != static_cast<std::size_t>(image.width) * image.height * image.channels)
    fail(fmt::format("texture: {}x{} image with {} channels is not uploadable", image.width,
                     image.height, image.channels));
  // Bottom row first (GL's row 0).
  const std::size_t row = static_cast<std::size_t>(image.width) * image.channels;
  std::vector<float> flipped(image.data.size());
  for (int r = 0; r < image.height; ++r)
    std::copy_n(image.data.data() + static_cast<std::size_t>(image.height - 1 - r) * row, row,
                flipped.data() + static_cast<std::size_t>(r) * row);
  glGenTextures(1, &id_);
  glBindTexture(GL_TEXTURE_2D, id_);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 4);
  glTexImage2D(GL_TEXTURE_2D, 0, kInternal[image.channels - 1], image.width, image.height, 0,
               kFormat[image.channels - 1], GL_FLOAT, flipped.data());
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    glDeleteTextures(1, &id_);
    fail(fmt::format("uploading a {}x{} float texture failed (GL error 0x{:04x})", image.width,
                     image.height, e));
  }
}

Texture::~Texture() {
  glDeleteTextures(1, &id_);
}

// ---- programs -----------------------------------------------------------------------------------

namespace {

GLuint compile(GLenum stage, std::string_view source) {
  const GLuint shader = glCreateShader(stage);
  const GLchar* text = source.data();
  const GLint length = static_cast<GLint>(source.size());
  glShaderSource(shader, 1, &text, &length);
  glCompileShader(shader);
  GLint ok = GL_FALSE;
  glGetShaderiv(shader, GL_COMPILE_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint n = 0;
    glGetShaderiv(shader, GL_INFO_LOG_LENGTH, &n);
    std::string log(static_cast<std::size_t>(std::max(n, 1)), '\0');
    glGetShaderInfoLog(shader, n, nullptr, log.data());
    glDeleteShader(shader);
    log.resize(std::strlen(log.c_str()));
    while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
    fail(fmt::format("{} shader does not compile: {}",
                     stage == GL_VERTEX_SHADER ? "vertex" : "fragment", log));
  }
  return shader;
}

}  // namespace

Program::Program(std::string_view vertex_source, std::string_view fragment_source) {
  const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source);
  GLuint fs = 0;
  try {
    fs = compile(GL_FRAGMENT_SHADER, fragment_source);
  } catch (...) {
    glDeleteShader(vs);
    throw;
  }
  id_ = glCreateProgram();
  glAttachShader(id_, vs);
  glAttachShader(id_, fs);
  glBindAttribLocation(id_, 0, "position");
  glBindAttribLocation(id_, 1, "attribute1");
  glLinkProgram(id_);
  glDeleteShader(vs);
  glDeleteShader(fs);
  GLint ok = GL_FALSE;
  glGetProgramiv(id_, GL_LINK_STATUS, &ok);
  if (ok != GL_TRUE) {
    GLint n = 0;
    glGetProgramiv(id_, GL_INFO_LOG_LENGTH, &n);
    std::string log(static_cast<std::size_t>(std::max(n, 1)), '\0');
    glGetProgramInfoLog(id_, n, nullptr, log.data());
    glDeleteProgram(id_);
    id_ = 0;
    log.resize(std::strlen(log.c_str()));
    while (!log.empty() && (log.back() == '\n' || log.back() == ' ')) log.pop_back();
    fail("program does not link: " + log);
  }
}

Program Program::fullscreen(std::string_view fragment_source) {
  return Program(kFullscreenVertexShader, fragment_source);
}

Program::~Program() {
  if (id_ != 0) glDeleteProgram(id_);
}

Program::Program(Program&& other) noexcept : id_(other.id_), textures_(std::move(other.textures_)) {
  other.id_ = 0;
}

void Program::set(std::string_view name, const UniformValue& value) {
  if (!set_if_active(name, value)) fail(fmt::format("the shader has no active uniform '{}'", name));
}

bool Program::set_if_active(std::string_view name, const UniformValue& value) {
  glUseProgram(id_);
  const GLint loc = glGetUniformLocation(id_, std::string(name).c_str());
  if (loc < 0) return false;
  std::visit(
      [loc](const auto& v) {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, int>) {
          glUniform1i(loc, v);
        } else if constexpr (std::is_same_v<T, float>) {
          glUniform1f(loc, v);
        } else if constexpr (std::is_same_v<T, std::array<float, 2>>) {
          glUniform2f(loc, v[0], v[1]);
        } else if constexpr (std::is_same_v<T, std::array<float, 3>>) {
          glUniform3f(loc, v[0], v[1], v[2]);
        } else {
          glUniform4f(loc, v[0], v[1], v[2], v[3]);
        }
      },
      value);
  check_gl("setting a uniform");
  return true;
}

void Program::bind(std::string_view name, const Texture& texture, int unit) {
  set(name, unit);
  std::erase_if(textures_, [unit](const auto& t) { return t.first == unit; });
  textures_.emplace_back(unit, texture.id());
}

// ---- render target ------------------------------------------------------------------------------

Target::Target(int width, int height) : width_(width), height_(height) {
  GLint max_size = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &max_size);
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    fail(fmt::format("render target {}x{} is outside 1..{} per side", width, height, max_size));
  glGenFramebuffers(1, &fbo_);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glGenRenderbuffers(1, &colour_);
  glBindRenderbuffer(GL_RENDERBUFFER, colour_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA32F, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_);
  glGenRenderbuffers(1, &depth_);
  glBindRenderbuffer(GL_RENDERBUFFER, depth_);
  glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
  glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_);
  const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE) {
    glDeleteFramebuffers(1, &fbo_);
    glDeleteRenderbuffers(1, &colour_);
    glDeleteRenderbuffers(1, &depth_);
    fail(fmt::format("RGBA32F framebuffer {}x{} is incomplete (status 0x{:04x})", width, height,
                     status));
  }
  check_gl("creating the render target");
}

Target::~Target() {
  glDeleteFramebuffers(1, &fbo_);
  glDeleteRenderbuffers(1, &colour_);
  glDeleteRenderbuffers(1, &depth_);
}

void Target::clear(std::array<float, 4> c) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glClearColor(c[0], c[1], c[2], c[3]);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
}

namespace {
void use(const Program& program, const std::vector<std::pair<int, unsigned>>& textures) {
  glUseProgram(program.id());
  for (const auto& [unit, id] : textures) {
    glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(unit));
    glBindTexture(GL_TEXTURE_2D, id);
  }
}
}  // namespace

void Target::draw_fullscreen(const Program& program) {
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glDisable(GL_DEPTH_TEST);
  use(program, program.textures_);
  glDrawArrays(GL_TRIANGLES, 0, 6);
  check_gl("drawing the full-screen quad");
}

void Target::draw_mesh(const Program& program, std::span<const float> positions,
                       std::span<const float> attribute1, std::span<const unsigned> indices) {
  if (positions.size() % 3 != 0 || (!attribute1.empty() && attribute1.size() != positions.size()))
    fail("mesh: positions and attribute 1 need 3 floats per vertex each");
  std::vector<Attribute> a{{3, positions}};
  if (!attribute1.empty()) a.push_back({3, attribute1});
  draw_mesh(program, a, indices);
}

void Target::draw_mesh(const Program& program, std::span<const Attribute> attributes,
                       std::span<const unsigned> indices) {
  if (attributes.empty()) fail("mesh: no vertex attributes");
  const auto c0 = static_cast<std::size_t>(attributes[0].components);
  if (c0 < 1 || c0 > 4) fail("mesh: an attribute has 1 to 4 floats per vertex");
  const std::size_t vertices = attributes[0].values.size() / c0;
  for (const Attribute& a : attributes)
    if (a.components < 1 || a.components > 4 ||
        a.values.size() != vertices * static_cast<std::size_t>(a.components))
      fail(fmt::format("mesh: every attribute needs {} vertices of 1 to 4 floats", vertices));
  for (unsigned i : indices)
    if (i >= vertices) fail(fmt::format("mesh: index {} beyond {} vertices", i, vertices));
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glViewport(0, 0, width_, height_);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  use(program, program.textures_);
  std::vector<GLuint> buffers(attributes.size() + 1, 0);
  glGenBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
  for (std::size_t k = 0; k < attributes.size(); ++k) {
    glBindBuffer(GL_ARRAY_BUFFER, buffers[k]);
    glBufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(attributes[k].values.size_bytes()),
                 attributes[k].values.data(), GL_STREAM_DRAW);
    glEnableVertexAttribArray(static_cast<GLuint>(k));
    glVertexAttribPointer(static_cast<GLuint>(k), attributes[k].components, GL_FLOAT, GL_FALSE, 0,
                          nullptr);
  }
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, buffers.back());
  glBufferData(GL_ELEMENT_ARRAY_BUFFER, static_cast<GLsizeiptr>(indices.size_bytes()),
               indices.data(), GL_STREAM_DRAW);
  glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(indices.size()), GL_UNSIGNED_INT, nullptr);
  for (std::size_t k = 0; k < attributes.size(); ++k)
    glDisableVertexAttribArray(static_cast<GLuint>(k));
  glBindBuffer(GL_ARRAY_BUFFER, 0);
  glBindBuffer(GL_ELEMENT_ARRAY_BUFFER, 0);
  glDeleteBuffers(static_cast<GLsizei>(buffers.size()), buffers.data());
  check_gl("drawing the mesh");
}

io::ImageF Target::read(int channels) const {
  if (channels < 1 || channels > 4) fail(fmt::format("read: {} channels", channels));
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  std::vector<float> rgba(static_cast<std::size_t>(width_) * height_ * 4);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_FLOAT, rgba.data());
  check_gl("reading the render target back");
  io::ImageF out(width_, height_, channels);
  for (int r = 0; r < height_; ++r) {
    const float* src = rgba.data() + static_cast<std::size_t>(height_ - 1 - r) * width_ * 4;
    float* dst = out.pixel(0, r);
    for (int c = 0; c < width_; ++c)
      for (int k = 0; k < channels; ++k) dst[c * channels + k] = src[c * 4 + k];
  }
  return out;
}

io::ImageF run_fullscreen(const FullscreenPass& pass, int width, int height, int channels) {
  Program program = Program::fullscreen(pass.fragment_source);
  for (const auto& [name, value] : pass.uniforms) program.set(name, value);
  std::vector<std::unique_ptr<Texture>> textures;
  for (const auto& [name, image] : pass.inputs) {
    textures.push_back(std::make_unique<Texture>(*image));
    program.bind(name, *textures.back(), static_cast<int>(textures.size()) - 1);
  }
  Target target(width, height);
  target.clear();
  target.draw_fullscreen(program);
  return target.read(channels);
}

}  // namespace skylight::gpu
