// Lantern: the whole public API in one include, except presentation in a window:
// lantern/Window.h (which includes vulkan.h) and lantern/glfw/GlfwWindow.h (Lantern::glfw).
#pragma once

#include <lantern/Camera.h>
#include <lantern/CameraConventions.h>
#include <lantern/Compare.h>
#include <lantern/Cryptomatte.h>
#include <lantern/Image.h>
#include <lantern/Io.h>
#include <lantern/Log.h>
#include <lantern/Renderer.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>
#include <lantern/Version.h>
