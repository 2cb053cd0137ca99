#pragma once
// Whether the calling thread has an OpenGL context current (EGL or GLX). Applications often end their
// context (glfwTerminate) before palpate's objects go out of scope: those objects went with the
// context, and a GL call then would abort inside the loader, so destructors ask first.
namespace palpate::gl {

bool a_context_is_current() noexcept;

}  // namespace palpate::gl
