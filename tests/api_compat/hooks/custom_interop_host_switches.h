// Sets the host interop build's feature switches (renderer::enabled_features) from a translation
// unit that includes the standard build.
#ifndef CUSTOM_INTEROP_HOST_SWITCHES_H
#define CUSTOM_INTEROP_HOST_SWITCHES_H
void custom_interop_set_enabled_features(unsigned mask);
#endif
