#pragma once

namespace baker {

// `baker relight VOLUME --env NEW.hdr --out OUT`: the volume under another sky, through each
// probe's stored visibility (relight/Relighting.h).
int runRelightCommand(int argc, char** argv);

}  // namespace baker
