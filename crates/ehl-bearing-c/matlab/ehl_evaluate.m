function [R, K, C, info] = ehl_evaluate(e, q, qdot, inner_speed_rad_s, outer_speed_rad_s, cage_angle_rad, state)
%EHL_EVALUATE  Evaluate a bearing force element.
%   [R, K, C] = EHL_EVALUATE(E, Q, QDOT, WI, WO, CAGE) at ring displacement Q (x, y, z in m;
%   theta_y, theta_z in rad; inner relative to outer ring, x axial), rates QDOT (m/s, rad/s;
%   [] for zero), ring speeds WI, WO (rad/s, default WO = 0) and cage angle CAGE (rad, default 0;
%   ball j at 2*pi*j/Z + CAGE). R (5x1) is the load on the inner ring (N, N*m; the bearing acts
%   on the shaft with -R), K = dR/dq and C = dR/dqdot (5x5, SI). INFO has outside_range,
%   overloaded (contact counts), speed_outside and cage_speed_rad_s (the cage speed at this
%   state from the bearing model's orbital speeds, rad/s).
%   EHL_EVALUATE(..., STATE) uses the warm-start state STATE (EHL_STATE) instead of the
%   element's own: one state per bearing and caller.
% Kept lean: in Octave every statement here costs microseconds (docs/matlab.md, cost per call).
if nargin < 7
  if isfield(e, 'state'), state = e.state; else, state = e.id; end
end
if nargin < 6, cage_angle_rad = 0; end
if nargin < 5, outer_speed_rad_s = 0; end
if nargin < 3 || isempty(qdot), qdot = [0 0 0 0 0]; end
% Ids rather than structs: passing a struct to a MEX file copies all its fields.
if nargout > 3
  [R, K, C, info] = ehl_mex('evaluate', e.id, state, q, qdot, inner_speed_rad_s, outer_speed_rad_s, cage_angle_rad);
else
  [R, K, C] = ehl_mex('evaluate', e.id, state, q, qdot, inner_speed_rad_s, outer_speed_rad_s, cage_angle_rad);
end
end
