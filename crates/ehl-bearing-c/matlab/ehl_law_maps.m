function maps = ehl_law_maps()
%EHL_LAW_MAPS  The law maps embedded in the library (method 'map'), in the order a query tries them.
%   MAPS = EHL_LAW_MAPS() is a struct array (cell array where their specs differ in fields) with
%   the keys of `ehl-bearing law-map info --json`: name, law, nodes, cpu_seconds (s),
%   nodes_not_converged, worst_node_rms_hat, worst_node_r_squared, spec (models, fixed groups,
%   axis: group, min, max, nodes, log; amplitude, points, grid, ...). Groups are dimensionless.
maps = jsondecode(ehl_mex('law_maps'));
end
