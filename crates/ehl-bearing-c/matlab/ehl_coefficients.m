function [co, csv] = ehl_coefficients(c, speeds_rpm, varargin)
%EHL_COEFFICIENTS  Linearized bearing stiffness and damping over speed.
%   CO = EHL_COEFFICIENTS(C, SPEEDS_RPM, 'method', M) from the coupled characterization at each
%   inner-ring speed (M as in EHL_CHARACTERIZE; default the case's).
%   CO = EHL_COEFFICIENTS(C, SPEEDS_RPM, 'element', E) from element E's equilibrium (no EHL run).
%   'progress', FN as in EHL_CHARACTERIZE. CO is a struct array: inner_speed_rpm,
%   inner_speed_rad_s, displacement (5x1), stiffness, damping, dry_stiffness (5x5), converged,
%   source. [CO, CSV] = ... also gives ROSS's bearing table as CSV text.
opts = struct('method', '', 'element', [], 'progress', []);
for i = 1:2:numel(varargin)
  opts.(varargin{i}) = varargin{i + 1};
end
json = ehl_mex_progress(opts.progress, 'coefficients', c, speeds_rpm, opts.method, opts.element);
co = jsondecode(json);
if nargout > 1
  csv = ehl_mex('ross_table', json);
end
end
