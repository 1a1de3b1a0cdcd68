function ehl_free(varargin)
%EHL_FREE  Release ehl-bearing objects (cases, elements with their state, states,
%   characterizations). EHL_FREE('all') releases every object. Freed objects' ids are errors
%   afterwards, never crashes.
if nargin == 1 && ischar(varargin{1}) && strcmp(varargin{1}, 'all')
  ehl_mex('clear');
else
  ehl_mex('free', varargin{:});
end
end
