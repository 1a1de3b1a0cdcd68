function varargout = ehl_mex_progress(progress, varargin)
%EHL_MEX_PROGRESS  ehl_mex(VARARGIN{:}, FN) with the user's PROGRESS function wrapped so that
%   its errors come back as themselves (not as a cancel).
ehl_progress_error();
if isempty(progress)
  fn = [];
else
  fn = @(json) ehl_progress_call(progress, json);
end
try
  [varargout{1:nargout}] = ehl_mex(varargin{:}, fn);
catch err
  user = ehl_progress_error();
  if ~isempty(user)
    rethrow(user);
  end
  rethrow(err);
end
end
