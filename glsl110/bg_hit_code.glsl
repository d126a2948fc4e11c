#version 110
// requires:
// The hit code in the w lane of the G-buffer's HIT slot packs three facts into one exact float:
// |code| = object index + 1 (+ 0.5 for a thin shape), and the sign says whether the ray arrived
// from outside (+) or from inside a closed object (-). Thin shapes are always "+": either side is lit.

float bg_hit_code(float index, bool thin, bool entering)
{
    if (thin)
        return index + 1.5;
    return entering ? index + 1.0 : -(index + 1.0);
}

float bg_hit_index(float code)
{
    return floor(abs(code)) - 1.0;
}

bool bg_hit_thin(float code)
{
    return fract(abs(code)) > 0.25;
}

// Direct light reaches thin shapes on either side and closed ones only from outside (section 7).
bool bg_hit_outside(float code)
{
    return code > 0.0;
}
