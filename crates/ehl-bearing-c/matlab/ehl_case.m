function c = ehl_case(source, inner_speed_rpm)
%EHL_CASE  A bearing case from a case file or TOML text.
%   C = EHL_CASE(FILE) reads and validates a case file (e.g. examples/7006.toml).
%   C = EHL_CASE(TOML) parses TOML text (any text with a newline or '=' that is not a file).
%   C = EHL_CASE(..., INNER_SPEED_RPM) sets the inner-ring speed, rpm.
%   C is a struct: id, type, ball_count, ball_diameter_m, pitch_diameter_m, contact_angle_rad,
%   inner_speed_rad_s, outer_speed_rad_s (SI). Release it with EHL_FREE.
%   Errors (ehl:input, ...) carry the library's message naming the field, value and range.
if ~ischar(source)
  error('ehl:usage', 'ehl_case: give a file name or TOML text');
end
if exist(source, 'file') == 2 || (~any(source == sprintf('\n')) && ~any(source == '='))
  c = ehl_mex('case_file', source);
else
  c = ehl_mex('case_toml', source);
end
if nargin > 1
  c2 = ehl_mex('case_speed', c, inner_speed_rpm);
  ehl_mex('free', c);
  c = c2;
end
end
