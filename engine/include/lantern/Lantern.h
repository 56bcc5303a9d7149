// Lantern: the whole public API in one include.
#pragma once

#include <lantern/Camera.h>
#include <lantern/Image.h>
#include <lantern/Io.h>
#include <lantern/Log.h>
#include <lantern/Renderer.h>
#include <lantern/Result.h>
#include <lantern/Scene.h>
#include <lantern/Version.h>
