function w = ehl_cage_speed(e, inner_speed_rad_s, outer_speed_rad_s)
%EHL_CAGE_SPEED  Cage speed under pure rolling, rad/s, at ring speeds WI, WO (rad/s).
if nargin < 3, outer_speed_rad_s = 0; end
w = ehl_mex('cage_speed', e, inner_speed_rad_s, outer_speed_rad_s);
end
