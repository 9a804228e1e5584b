#pragma once
// The consumer's own GL context (OSMesa), standing for an engine's window or off-screen layer.
bool createEngineContext(int width, int height);
void (*engineProcAddress(const char* name))();
void destroyEngineContext();
