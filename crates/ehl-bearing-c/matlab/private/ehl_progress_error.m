function err = ehl_progress_error(set)
%EHL_PROGRESS_ERROR  EHL_PROGRESS_ERROR(ERR) keeps the progress function's error;
%   ERR = EHL_PROGRESS_ERROR() returns it (or []) and forgets it.
persistent kept
if nargin > 0
  kept = set;
  return
end
err = kept;
kept = [];
end
